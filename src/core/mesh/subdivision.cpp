#include "ibfvs/core/mesh/subdivision.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/limits.h"
#include "openmesh_errors.h"

namespace ibfvs {
namespace {

using OmTriMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// Builds an OpenMesh mesh with the given per-vertex "points" (positions or any
// other three channels of vertex data) on the connectivity of `mesh`. A face
// OpenMesh cannot join to its manifold connectivity (a third face on an edge,
// a duplicate) gets its own copies of its vertices rather than being dropped,
// as OpenMesh's file importer does; every channel is built the same way, so
// the copies line up. Returns the number of such faces in `split`.
OmTriMesh build(const TriMesh& mesh, const std::vector<glm::vec3>& points, std::size_t* split) {
  OmTriMesh om;
  om.reserve(points.size(), 3 * mesh.triangles.size(), mesh.triangles.size());
  for (const glm::vec3& p : points) om.add_vertex(OmTriMesh::Point(p.x, p.y, p.z));
  std::size_t n_split = 0;
  OmErrCapture quiet;  // add_face reports each refusal on omerr
  for (const Triangle& t : mesh.triangles) {
    const auto fh = om.add_face(OmTriMesh::VertexHandle(static_cast<int>(t[0])),
                                OmTriMesh::VertexHandle(static_cast<int>(t[1])),
                                OmTriMesh::VertexHandle(static_cast<int>(t[2])));
    if (fh.is_valid()) continue;
    OmTriMesh::VertexHandle copy[3];
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& p = points[t[k]];
      copy[k] = om.add_vertex(OmTriMesh::Point(p.x, p.y, p.z));
    }
    om.add_face(copy[0], copy[1], copy[2]);
    ++n_split;
  }
  if (split) *split = n_split;
  return om;
}

std::vector<glm::vec3> subdivided_points(const TriMesh& mesh, const std::vector<glm::vec3>& points,
                                         int levels, std::vector<Triangle>* triangles) {
  OmTriMesh om = build(mesh, points, nullptr);
  OpenMesh::Subdivider::Uniform::LoopT<OmTriMesh> loop;
  loop.attach(om);
  loop(static_cast<std::size_t>(levels));
  loop.detach();
  om.garbage_collection();
  std::vector<glm::vec3> out(om.n_vertices());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto& p = om.point(OmTriMesh::VertexHandle(static_cast<int>(i)));
    out[i] = glm::vec3(p[0], p[1], p[2]);
  }
  if (triangles) {
    triangles->clear();
    triangles->reserve(om.n_faces());
    for (const auto fh : om.faces()) {
      Triangle t{};
      int k = 0;
      for (const auto vh : om.fv_range(fh)) t[k++] = static_cast<std::uint32_t>(vh.idx());
      triangles->push_back(t);
    }
  }
  return out;
}

}  // namespace

TriMesh loop_subdivide(const TriMesh& mesh, int levels) {
  if (levels < 0 || levels > 12) throw SettingError("subdivide", "levels must be between 0 and 12");
  try {
    check_memory(mesh_bytes(subdivided_triangles(mesh.triangle_count(), levels)),
                 std::to_string(levels) + " levels of a mesh of " +
                     std::to_string(mesh.triangle_count()) + " triangles");
  } catch (const InputError& e) {
    throw SettingError("subdivide", e.what());
  }
  if (levels == 0) return mesh;
  TriMesh out;
  out.positions = subdivided_points(mesh, mesh.positions, levels, &out.triangles);
  // OpenMesh drops faces it cannot add (non-manifold); the data channels are
  // run through the same connectivity, so they line up with the positions.
  if (mesh.vectors.size() == mesh.positions.size())
    out.vectors = subdivided_points(mesh, mesh.vectors, levels, nullptr);
  for (const auto& [name, values] : mesh.vector_arrays)
    out.vector_arrays[name] = subdivided_points(mesh, values, levels, nullptr);
  out.other_arrays = mesh.other_arrays;
  std::vector<std::pair<std::string, std::vector<float>>> scalars(mesh.scalars.begin(),
                                                                  mesh.scalars.end());
  for (std::size_t s = 0; s < scalars.size(); s += 3) {
    std::vector<glm::vec3> packed(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t c = 0; c < 3 && s + c < scalars.size(); ++c)
      for (std::size_t i = 0; i < packed.size(); ++i)
        packed[i][static_cast<int>(c)] = scalars[s + c].second[i];
    const std::vector<glm::vec3> result = subdivided_points(mesh, packed, levels, nullptr);
    for (std::size_t c = 0; c < 3 && s + c < scalars.size(); ++c) {
      std::vector<float>& values = out.scalars[scalars[s + c].first];
      values.resize(result.size());
      for (std::size_t i = 0; i < result.size(); ++i) values[i] = result[i][static_cast<int>(c)];
    }
  }
  if (out.triangles.empty()) throw SettingError("subdivide", "OpenMesh could not build the mesh");
  compute_vertex_normals(out);
  return out;
}

}  // namespace ibfvs
