#pragma once
// A mesh with every array in the byte form a reading child hands back
// (support/isolation.h).

#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/support/isolation.h"

namespace ibfvs {

/// Writes the mesh: positions, normals, triangles, vectors and every named array.
void put_mesh(ByteWriter& out, const TriMesh& mesh);
/// Reads what put_mesh wrote; throws InputError on a short or inconsistent record.
TriMesh get_mesh(ByteReader& in);

}  // namespace ibfvs
