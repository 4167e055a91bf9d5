#include "project/synthesizer_pool.h"

namespace terrasynth::project {

Result<Synthesizer*> SynthesizerPool::forThisThread() {
    std::lock_guard<std::mutex> lock(mutex_);
    auto& slot = synthesizers_[std::this_thread::get_id()];
    if (!slot) {
        auto created = Synthesizer::create(db_, options_);
        if (!created) return created.status();
        slot = std::move(created.value());
    }
    return slot.get();
}

}  // namespace terrasynth::project
