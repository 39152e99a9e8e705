#pragma once
// Mesh preparation for the GPU, done once at load: what triangle strips were
// in 2003 (paper section 5), vertex-cache and vertex-fetch ordering are now
// (meshoptimizer, A. Kapoulkine; Forsyth's and Tom's cache algorithms).

#include <algorithm>
#include <vector>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// Average cache miss ratio (transformed vertices per triangle, 0.5..3) of
/// the index order for a FIFO vertex cache of 16 entries.
float vertex_cache_acmr(const TriMesh& mesh);

/// Reorders the triangles for the post-transform vertex cache and then the
/// vertices for memory locality (every per-vertex array: positions, normals,
/// vectors, scalars, moves with them). Unreferenced vertices are dropped.
/// The surface is unchanged; only the order is. Returns the new index of
/// every old vertex (~0u for a dropped one), to reorder other per-vertex data
/// the same way (remap_vertex_data).
std::vector<unsigned> optimize_for_gpu(TriMesh& mesh);

/// Reorders per-vertex data with the result of optimize_for_gpu.
template <class T>
std::vector<T> remap_vertex_data(const std::vector<T>& values, const std::vector<unsigned>& order) {
  std::size_t count = 0;
  for (const unsigned k : order)
    if (k != ~0u) count = std::max<std::size_t>(count, k + 1);
  std::vector<T> out(count);
  for (std::size_t i = 0; i < values.size() && i < order.size(); ++i)
    if (order[i] != ~0u) out[order[i]] = values[i];
  return out;
}

}  // namespace ibfvs
