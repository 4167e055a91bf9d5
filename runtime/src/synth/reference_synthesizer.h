// Private: factory of the plain C++ backend (SynthesisBackend::Reference).
#pragma once

#include <memory>

#include "terrasynth/synthesizer.h"

namespace terrasynth::synth {

std::unique_ptr<Synthesizer> createReferenceSynthesizer(std::shared_ptr<const ExemplarDatabase> db);

}  // namespace terrasynth::synth
