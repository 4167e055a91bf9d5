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
    if (options.backend == SynthesisBackend::Reference)
        return std::unique_ptr<Synthesizer>(synth::createReferenceSynthesizer(std::move(db)));
#if TERRASYNTH_HAVE_OPENCL
    return cl::createOpenClSynthesizer(std::move(db), options);
#else
    return Status::error("this build has no OpenCL backend (built with TERRASYNTH_WITH_OPENCL=OFF); "
                         "use the reference backend");
#endif
}

}  // namespace terrasynth
