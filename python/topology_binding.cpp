// ibfvs.topology's native half: a scene prepared as an Animation prepares
// it (a file, or arrays), the skin-friction topology of each of its steps
// (core/fields/topology.h; ids carried from step to step) laid out as `ibfvs
// topology` writes it (core/fields/topology_layout.h, the one layout), as
// numpy arrays.
#include "topology_binding.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "ibfvs/core/fields/topology.h"
#include "ibfvs/core/fields/topology_layout.h"
#include "ibfvs/core/scene/scene_prep.h"

namespace ibfvs::python {
namespace {

template <class T>
py::array_t<T> array_of(std::vector<py::ssize_t> shape, const std::vector<T>& values) {
  py::array_t<T> out(shape);
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

py::dict step_dict(const FlowTopology& t, const TriMesh& mesh, const std::string& name) {
  const TopologyLayout g = topology_layout(t, name + ": " + topology_summary(t, mesh));
  const auto n = static_cast<py::ssize_t>(g.point_count());
  const auto c = static_cast<py::ssize_t>(g.cell_count());
  py::dict d;
  d["points"] = array_of<float>({n, 3}, g.points);
  d["normals"] = array_of<float>({n, 3}, g.normals);
  d["index"] = array_of<std::int32_t>({n}, g.index);
  d["magnitude"] = array_of<float>({n}, g.magnitude);
  d["eigenvalues"] = array_of<double>({n, 4}, g.eigenvalues);
  d["vert_offsets"] =
      array_of<std::int64_t>({static_cast<py::ssize_t>(g.vert_offsets.size())}, g.vert_offsets);
  d["vert_connectivity"] = array_of<std::int64_t>(
      {static_cast<py::ssize_t>(g.vert_connectivity.size())}, g.vert_connectivity);
  d["line_offsets"] =
      array_of<std::int64_t>({static_cast<py::ssize_t>(g.line_offsets.size())}, g.line_offsets);
  d["line_connectivity"] = array_of<std::int64_t>(
      {static_cast<py::ssize_t>(g.line_connectivity.size())}, g.line_connectivity);
  d["kind"] = array_of<std::int32_t>({c}, g.kind);
  d["id"] = array_of<std::int32_t>({c}, g.id);
  d["origin"] = array_of<std::int32_t>({c}, g.origin);
  d["strength"] = array_of<double>({c}, g.strength);
  d["length"] = array_of<double>({c}, g.length);
  d["colour"] = array_of<std::uint8_t>({c, 3}, g.colour);
  std::vector<std::uint8_t> closed;
  for (const FeatureLine& l : t.lines.lines) closed.push_back(l.closed ? 1 : 0);
  d["closed"] = array_of<std::uint8_t>({static_cast<py::ssize_t>(closed.size())}, closed);
  d["summary"] = g.summary;
  d["index_sum"] = t.critical.index_sum;
  d["euler_characteristic"] = euler_characteristic(mesh);
  d["degenerate_triangles"] = t.critical.degenerate_triangles;
  d["zero_triangles"] = t.critical.zero_triangles;
  d["cancelled"] = t.critical.cancelled;
  d["on_lines"] = t.critical.on_lines;
  d["scale"] = t.lines.scale;
  return d;
}

}  // namespace

py::dict topology_of(const PreparedScene& prepared, const TopologyOptions& options) {
  check_topology_options(options);
  py::list steps;
  std::optional<FlowTopology> before;
  int next_id = 0;
  const std::size_t count = std::max<std::size_t>(prepared.step_count, 1);
  for (std::size_t k = 0; k < count; ++k) {
    const StepData step = k == 0 ? StepData{} : prepared.step_data(k);
    const TriMesh surface = k == 0 ? *prepared.mesh : step_surface(prepared, step);
    const std::span<const glm::vec3> field = k == 0 ? std::span<const glm::vec3>(prepared.field)
                                                    : std::span<const glm::vec3>(step.field);
    FlowTopology t;
    {
      py::gil_scoped_release release;
      t = find_topology(surface, field, options);
    }
    if (before)
      carry_ids(*before, t, next_id, 2.0 * t.lines.scale);
    else
      next_id = static_cast<int>(t.critical.points.size() + t.lines.lines.size());
    const std::string name =
        count > 1 ? prepared.mesh_name + " step " + std::to_string(k) : prepared.mesh_name;
    steps.append(step_dict(t, surface, name));
    before = std::move(t);
  }
  py::dict out;
  out["steps"] = steps;
  out["warnings"] = prepared.warnings;
  return out;
}

}  // namespace ibfvs::python
