#pragma once
// ibfvs.topology's native half (topology_binding.cpp).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace ibfvs {
struct PreparedScene;
}

namespace ibfvs::python {
namespace py = pybind11;

/// The topology of a prepared scene's field at its first step: critical
/// points (points, kind, index, eigenvalues), lines (a list of dicts) and
/// the summary line.
py::dict topology_of(const PreparedScene& prepared, double min_strength, double min_length);

}  // namespace ibfvs::python
