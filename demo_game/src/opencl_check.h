// Whether an OpenCL device exists, asked of the ICD loader directly (the runtime only finds out when
// its first synthesizer is created, which needs the database and may be after a window opened).
#pragma once

#include "terrasynth/status.h"

namespace terrasynth::game {

// Ok when at least one OpenCL platform has a device; otherwise the loader's answer. An error in
// builds without OpenCL (the reference backend is then the only one).
Status checkOpenClDevice();

}  // namespace terrasynth::game
