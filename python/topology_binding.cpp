// ibfvs.topology's native half: a scene prepared as an Animation prepares
// it (a file, or arrays), its critical points and separation and attachment
// lines (core/fields/topology.h) as numpy arrays.
#include "topology_binding.h"

#include <algorithm>
#include <vector>

#include "ibfvs/core/fields/topology.h"
#include "ibfvs/core/scene/scene_prep.h"

namespace ibfvs::python {
namespace {

// Arrays by shape (numpy works out the strides: see int64_array).
template <class T>
py::array_t<T> array_of(std::vector<py::ssize_t> shape, const std::vector<T>& values) {
  py::array_t<T> out(shape);
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

}  // namespace

py::dict topology_of(const PreparedScene& prepared, double min_strength, double min_length) {
  const TriMesh& mesh = *prepared.mesh;
  const FlowTopology t = find_topology(mesh, prepared.field, {min_strength, min_length});
  const auto k = static_cast<py::ssize_t>(t.critical.points.size());
  std::vector<double> xyz, normals, eigen;
  std::vector<std::int32_t> kind, index;
  for (const CriticalPoint& p : t.critical.points) {
    xyz.insert(xyz.end(), {p.position.x, p.position.y, p.position.z});
    normals.insert(normals.end(), {p.normal.x, p.normal.y, p.normal.z});
    eigen.insert(eigen.end(), {p.eigen_real[0], p.eigen_imag[0], p.eigen_real[1], p.eigen_imag[1]});
    kind.push_back(static_cast<std::int32_t>(p.kind));
    index.push_back(p.index);
  }
  py::list lines;
  for (const FeatureLine& l : t.lines.lines) {
    std::vector<double> at, up, ev;
    std::vector<float> magnitude;
    for (const LinePoint& p : l.points) {
      at.insert(at.end(), {p.position.x, p.position.y, p.position.z});
      up.insert(up.end(), {p.normal.x, p.normal.y, p.normal.z});
      ev.insert(ev.end(), {p.eigen[0], p.eigen[1]});
      magnitude.push_back(p.magnitude);
    }
    const auto n = static_cast<py::ssize_t>(l.points.size());
    py::dict line;
    line["kind"] = static_cast<int>(l.kind);
    line["points"] = array_of<double>({n, 3}, at);
    line["normals"] = array_of<double>({n, 3}, up);
    line["magnitude"] = array_of<float>({n}, magnitude);
    line["eigenvalues"] = array_of<double>({n, 2}, ev);
    line["closed"] = l.closed;
    line["strength"] = l.strength;
    line["length"] = l.length;
    lines.append(line);
  }
  py::dict out;
  out["points"] = array_of<double>({k, 3}, xyz);
  out["normals"] = array_of<double>({k, 3}, normals);
  out["kind"] = array_of<std::int32_t>({k}, kind);
  out["index"] = array_of<std::int32_t>({k}, index);
  out["eigenvalues"] = array_of<double>({k, 4}, eigen);
  out["lines"] = lines;
  out["index_sum"] = t.critical.index_sum;
  out["euler_characteristic"] = euler_characteristic(mesh);
  out["degenerate_triangles"] = t.critical.degenerate_triangles;
  out["zero_triangles"] = t.critical.zero_triangles;
  out["summary"] = prepared.mesh_name + ": " + topology_summary(t, mesh);
  return out;
}

}  // namespace ibfvs::python
