#pragma once
// Mesh preparation for the GPU, done once at load: what triangle strips were
// in 2003 (paper section 5), vertex-cache and vertex-fetch ordering are now
// (meshoptimizer, A. Kapoulkine; Forsyth's and Tom's cache algorithms).

#include "ibfvs/core/mesh.h"

namespace ibfvs {

/// Average cache miss ratio (transformed vertices per triangle, 0.5..3) of
/// the index order for a FIFO vertex cache of 16 entries.
float vertex_cache_acmr(const TriMesh& mesh);

/// Reorders the triangles for the post-transform vertex cache and then the
/// vertices for memory locality (every per-vertex array: positions, normals,
/// vectors, scalars, moves with them). Unreferenced vertices are dropped.
/// The surface is unchanged; only the order is.
void optimize_for_gpu(TriMesh& mesh);

}  // namespace ibfvs
