#pragma once
// Loop subdivision (C. Loop, "Smooth subdivision surfaces based on triangles",
// 1987; paper section 5) through OpenMesh, carrying per-vertex data along.

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// Subdivides `levels` times (each level multiplies the triangle count by 4).
/// Per-vertex vectors and scalars are subdivided with the same Loop masks as
/// the positions (Loop is linear in the vertex data), so a field read from a
/// file stays consistent. Normals are recomputed. Throws InputError for
/// levels outside [0, 8] or a mesh OpenMesh cannot build.
TriMesh loop_subdivide(const TriMesh& mesh, int levels);

}  // namespace ibfvs
