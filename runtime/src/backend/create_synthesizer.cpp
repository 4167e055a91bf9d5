// Synthesizer::create: the one place that knows both backends, so the C++ reference backend
// (module synth) can be had in a build without OpenCL (TERRASYNTH_WITH_OPENCL=OFF).
#include "terrasynth/synthesizer.h"

#include "synth/reference_synthesizer.h"
#if TERRASYNTH_HAVE_OPENCL
#include "cl/cl_synthesizer.h"
#endif

namespace terrasynth {

Result<std::unique_ptr<Synthesizer>> Synthesizer::create(std::shared_ptr<const ExemplarDatabase> db,
                                                         const SynthesizerOptions& options) {
    TERRASYNTH_REQUIRE(db != nullptr, "Synthesizer::create needs a database");
    if (db->levels.empty()) return Status::error("database has no levels");
    std::unique_ptr<Synthesizer> synthesizer;
    if (options.backend == SynthesisBackend::Reference) {
        synthesizer = synth::createReferenceSynthesizer(std::move(db));
    } else {
#if TERRASYNTH_HAVE_OPENCL
        auto created = cl::createOpenClSynthesizer(std::move(db), options);
        if (!created) return created.status();
        synthesizer = std::move(created.value());
#else
        return Status::error("this build has no OpenCL backend (built with TERRASYNTH_WITH_OPENCL=OFF); "
                             "use the reference backend");
#endif
    }
    synthesizer->stop_requested_ = options.stop_requested;
    return synthesizer;
}

}  // namespace terrasynth
