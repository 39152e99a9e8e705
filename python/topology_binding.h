#pragma once
// ibfvs.topology's native half (topology_binding.cpp).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace ibfvs {
struct PreparedScene;
struct TopologyOptions;
}  // namespace ibfvs

namespace ibfvs::python {
namespace py = pybind11;

/// The topology of a prepared scene's field at each of its steps (ids kept
/// from step to step): {"steps": [the layout's arrays, the summary and the
/// counts, a dict a step], "warnings": the preparation's}. Throws
/// InputError for options out of range.
py::dict topology_of(const PreparedScene& prepared, const TopologyOptions& options);

}  // namespace ibfvs::python
