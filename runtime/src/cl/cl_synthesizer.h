// Private: factory of the OpenCL backend (SynthesisBackend::OpenCL), called by Synthesizer::create.
#pragma once

#include <memory>

#include "terrasynth/synthesizer.h"

namespace terrasynth::cl {

// Picks the device (options.device, TERRASYNTH_OPENCL_DEVICE), uploads the database and builds the
// kernels. Errors: no platform or device, kernel build log, out of device memory.
Result<std::unique_ptr<Synthesizer>> createOpenClSynthesizer(std::shared_ptr<const ExemplarDatabase> db,
                                                             const SynthesizerOptions& options);

}  // namespace terrasynth::cl
