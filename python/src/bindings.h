// The parts of the terrasynth Python module, each adding its classes and functions to it.
#pragma once

#include <optional>
#include <string>
#include <tuple>

#include <pybind11/pybind11.h>

#include "calls.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth::python {

// terrasynth.Project (a Terrain), open(), from_database().
void bindProject(py::module_& m);
// terrasynth.Session (an EditSession), edit().
void bindSession(py::module_& m);
// build_database(), write_heightmap().
void bindTools(py::module_& m);

// The synthesizer every object of the module uses: `backend` "opencl" or "reference", `device` as
// SynthesizerOptions::device, stopped by Ctrl-C (interruptHook).
SynthesizerOptions synthesizerOptions(const std::string& backend, const std::string& device);

// The window a heights() call names: (x, y, width, height) given together, or none of them for the
// project's extent at `level` (as `terrasynth synth` writes it).
PixelWindow requestedWindow(const PixelWindow& extent, std::optional<int64_t> x, std::optional<int64_t> y,
                            std::optional<int64_t> width, std::optional<int64_t> height, int level);

// Runtime warnings (a stale edited-heights sidecar) as Python UserWarnings.
void warnEach(const std::vector<std::string>& warnings);

}  // namespace terrasynth::python
