// The terrasynth Python module (docs/python.md): the runtime's public API for scripts and pipelines,
// numpy in and out. No terrain code lives here; every call goes to the runtime as the CLI's do.
#include <pybind11/pybind11.h>

#include "bindings.h"

namespace terrasynth::python {

SynthesizerOptions synthesizerOptions(const std::string& backend, const std::string& device) {
    SynthesizerOptions options;
    if (backend == "reference") options.backend = SynthesisBackend::Reference;
    else if (backend != "opencl") throw py::value_error("backend: expected 'opencl' or 'reference', got '" + backend + "'");
    options.device = device;
    options.stop_requested = interruptHook();
    return options;
}

}  // namespace terrasynth::python

PYBIND11_MODULE(terrasynth, m) {
    namespace py = pybind11;
    using namespace terrasynth::python;
    m.doc() =
        "terrasynth: terrain synthesis by example (Gain, Merry & Marais 2015) and layer editing (Bradbury et "
        "al. 2014) from Python. open() a project for heights, sources and types as numpy arrays and for "
        "exports (glTF, engine heightmaps, GeoTIFF); edit() it as the editor does; build_database() from "
        "exemplar DEMs. Runtime errors raise terrasynth.Error with the runtime's message; bad arguments "
        "raise ValueError; Ctrl-C stops a synthesis between two pyramid levels (KeyboardInterrupt).";
    m.attr("__version__") = TERRASYNTH_VERSION;
    py::register_exception<RuntimeFailure>(m, "Error", PyExc_RuntimeError)
        .attr("__doc__") = "A runtime error (a RuntimeError): its message is the runtime's, naming the file or "
                           "argument and the problem (a corrupt exemplar, a malformed project, no OpenCL device).";
    recordMainThread(py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>());
    bindProject(m);
    bindSession(m);
    bindTools(m);
}
