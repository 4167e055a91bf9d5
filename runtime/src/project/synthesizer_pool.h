// Private: one Synthesizer per calling thread (a Synthesizer owns an OpenCL queue and scratch and is
// not thread-safe), created on first use, shared by a Terrain and an edit session's snapshots.
#pragma once

#include <memory>
#include <mutex>
#include <thread>
#include <unordered_map>

#include "terrasynth/synthesizer.h"

namespace terrasynth::project {

class SynthesizerPool {
public:
    SynthesizerPool(std::shared_ptr<const ExemplarDatabase> db, SynthesizerOptions options)
        : db_(std::move(db)), options_(std::move(options)) {}
    // This thread's synthesizer. Thread-safe. Errors: those of Synthesizer::create.
    Result<Synthesizer*> forThisThread();
    // forThisThread made now, its synthesizer unused (Terrain's and EditSession's prepareThisThread).
    Status prepareThisThread() {
        auto synthesizer = forThisThread();
        return synthesizer ? Status::ok() : synthesizer.status();
    }
    // A synthesizer nobody else uses (an edit thread's own). Errors: those of Synthesizer::create.
    Result<std::unique_ptr<Synthesizer>> createPrivate() const { return Synthesizer::create(db_, options_); }
    const ExemplarDatabase& database() const { return *db_; }
    const std::shared_ptr<const ExemplarDatabase>& databasePtr() const { return db_; }

private:
    std::shared_ptr<const ExemplarDatabase> db_;
    SynthesizerOptions options_;
    std::mutex mutex_;
    std::unordered_map<std::thread::id, std::unique_ptr<Synthesizer>> synthesizers_;
};

}  // namespace terrasynth::project
