#include "ibfvs/core/mesh/gpu_prep.h"

#include <meshoptimizer.h>

namespace ibfvs {
namespace {

template <class T>
void remap(std::vector<T>& values, const std::vector<unsigned>& map, std::size_t count) {
  if (values.empty()) return;
  std::vector<T> out(count);
  for (std::size_t i = 0; i < values.size(); ++i)
    if (map[i] != ~0u) out[map[i]] = values[i];
  values = std::move(out);
}

}  // namespace

float vertex_cache_acmr(const TriMesh& mesh) {
  const auto* indices = reinterpret_cast<const unsigned*>(mesh.triangles.data());
  return meshopt_analyzeVertexCache(indices, mesh.triangles.size() * 3, mesh.vertex_count(), 16, 0,
                                    0)
      .acmr;
}

std::vector<unsigned> optimize_for_gpu(TriMesh& mesh) {
  static_assert(sizeof(Triangle) == 3 * sizeof(unsigned));
  auto* indices = reinterpret_cast<unsigned*>(mesh.triangles.data());
  const std::size_t index_count = mesh.triangles.size() * 3;
  const std::size_t n = mesh.vertex_count();
  meshopt_optimizeVertexCache(indices, indices, index_count, n);
  std::vector<unsigned> map(n);
  const std::size_t kept = meshopt_optimizeVertexFetchRemap(map.data(), indices, index_count, n);
  meshopt_remapIndexBuffer(indices, indices, index_count, map.data());
  remap(mesh.positions, map, kept);
  remap(mesh.normals, map, kept);
  remap(mesh.vectors, map, kept);
  for (auto& [name, values] : mesh.scalars) remap(values, map, kept);
  for (auto& [name, values] : mesh.vector_arrays) remap(values, map, kept);
  return map;
}

}  // namespace ibfvs
