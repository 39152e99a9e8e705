#include "ibfvs/core/mesh/mesh_bytes.h"

namespace ibfvs {

void put_mesh(ByteWriter& out, const TriMesh& mesh) {
  out.put(mesh.positions);
  out.put(mesh.normals);
  out.put(mesh.triangles);
  out.put(mesh.vectors);
  out.put<std::uint64_t>(mesh.scalars.size());
  for (const auto& [name, values] : mesh.scalars) {
    out.put(name);
    out.put(values);
  }
  out.put<std::uint64_t>(mesh.vector_arrays.size());
  for (const auto& [name, values] : mesh.vector_arrays) {
    out.put(name);
    out.put(values);
  }
  out.put<std::uint64_t>(mesh.other_arrays.size());
  for (const auto& [name, components] : mesh.other_arrays) {
    out.put(name);
    out.put<std::int32_t>(components);
  }
}

TriMesh get_mesh(ByteReader& in) {
  TriMesh mesh;
  mesh.positions = in.get_vector<glm::vec3>();
  mesh.normals = in.get_vector<glm::vec3>();
  mesh.triangles = in.get_vector<Triangle>();
  mesh.vectors = in.get_vector<glm::vec3>();
  for (auto n = in.get<std::uint64_t>(); n > 0; --n) {
    std::string name = in.get_string();
    mesh.scalars[name] = in.get_vector<float>();
  }
  for (auto n = in.get<std::uint64_t>(); n > 0; --n) {
    std::string name = in.get_string();
    mesh.vector_arrays[name] = in.get_vector<glm::vec3>();
  }
  for (auto n = in.get<std::uint64_t>(); n > 0; --n) {
    std::string name = in.get_string();
    mesh.other_arrays[name] = in.get<std::int32_t>();
  }
  return mesh;
}

}  // namespace ibfvs
