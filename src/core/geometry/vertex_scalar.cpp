#include "ibfvs/core/geometry/vertex_scalar.h"

#include <string>

#include <glm/geometric.hpp>

#include "ibfvs/core/geometry/curvature.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {

std::vector<float> vertex_scalar(const TriMesh& mesh, const std::vector<glm::vec3>& field,
                                 std::string_view name) {
  if (!name.empty() && name[0] == '-') {
    std::vector<float> v = vertex_scalar(mesh, field, name.substr(1));
    for (float& x : v) x = -x;
    return v;
  }
  const std::string key(name);
  if (const auto it = mesh.scalars.find(key); it != mesh.scalars.end()) return it->second;
  std::vector<float> out(mesh.vertex_count());
  if (key == "speed") {
    if (field.size() != out.size()) throw InputError("scalar 'speed': no field to measure");
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::length(field[i]);
    return out;
  }
  if (key == "kmin" || key == "kmax") {
    const Curvature c = mesh_curvature(mesh);
    return key == "kmin" ? c.kmin : c.kmax;
  }
  if (key == "x" || key == "y" || key == "z") {
    const int axis = key[0] - 'x';
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = mesh.positions[i][axis];
    return out;
  }
  // A vector array by name: its magnitude (as ParaView colours by it).
  if (const auto it = mesh.vector_arrays.find(key); it != mesh.vector_arrays.end()) {
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::length(it->second[i]);
    return out;
  }
  if (const auto it = mesh.other_arrays.find(key); it != mesh.other_arrays.end())
    throw InputError("the array '" + key + "' has " + std::to_string(it->second) +
                     " components; a scalar needs 1 (or 3, for the magnitude)");
  std::string known = "speed, kmin, kmax, x, y, z";
  for (const auto& [n, v] : mesh.scalars) known += ", " + n;
  for (const auto& [n, v] : mesh.vector_arrays) known += ", " + n + " (magnitude)";
  throw InputError("no per-vertex scalar '" + key + "' (available: " + known + ")");
}

}  // namespace ibfvs
