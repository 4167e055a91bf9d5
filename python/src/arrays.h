// numpy arrays in and out of the Python module, without copying what the runtime returns.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "terrasynth/heightfield.h"

namespace terrasynth::python {

namespace py = pybind11;

// A rows x cols C-contiguous array that owns `values` (moved, not copied).
template <class T>
py::array_t<T> toArray(std::vector<T>&& values, int rows, int cols) {
    auto* owned = new std::vector<T>(std::move(values));
    py::capsule release(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>({rows, cols}, owned->data(), release);
}
inline py::array_t<float> heightsArray(Heightfield&& field) {
    const int rows = field.height, cols = field.width;
    return toArray(std::move(field.heights), rows, cols);
}

// A (N, 2) array of float64 (or anything numpy turns into one: a list of pairs) as pairs.
inline std::vector<std::array<double, 2>> pointsFrom(const py::array_t<double, py::array::c_style | py::array::forcecast>& points,
                                                     const char* name) {
    if (points.ndim() != 2 || points.shape(1) != 2)
        throw py::value_error(std::string(name) + ": expected an (N, 2) array of x, y");
    std::vector<std::array<double, 2>> out(static_cast<size_t>(points.shape(0)));
    auto view = points.unchecked<2>();
    for (py::ssize_t i = 0; i < points.shape(0); ++i) out[i] = {view(i, 0), view(i, 1)};
    return out;
}
inline std::vector<std::pair<double, double>> pairsFrom(const py::array_t<double, py::array::c_style | py::array::forcecast>& points,
                                                        const char* name) {
    std::vector<std::pair<double, double>> out;
    for (const auto& p : pointsFrom(points, name)) out.emplace_back(p[0], p[1]);
    return out;
}

}  // namespace terrasynth::python
