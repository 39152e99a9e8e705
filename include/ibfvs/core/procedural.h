#pragma once
// Procedural meshes built in code: the demo's fallback surface when the fetched
// data is missing, and the analytic surfaces the tests measure against.

#include "ibfvs/core/mesh.h"

namespace ibfvs {

/// Torus around the Y axis: tube radius r, centre-line radius R, with
/// `segments` steps around Y and `sides` around the tube. Normals are exact.
TriMesh make_torus(float R, float r, int segments, int sides);

/// UV sphere of radius `radius` centred at the origin, with analytic normals.
/// `bump` > 0 adds a smooth radial relief of that relative amplitude
/// (normals then computed from the triangles).
TriMesh make_sphere(float radius, int stacks, int slices, float bump = 0.0f);

/// Square [-half, half]^2 in the plane z = 0, facing +Z, n x n cells.
TriMesh make_square(float half, int n);

/// Open cylinder around the Y axis, radius r, height h, centred at the origin.
TriMesh make_cylinder(float r, float h, int segments, int rings);

/// Regular icosahedron with vertices on the sphere of radius `radius`.
TriMesh make_icosahedron(float radius);

/// Height field z = f(x, y) over [-half, half]^2, n x n cells, normals
/// computed from the triangles.
TriMesh make_height_field(float (*f)(float, float), float half, int n);

}  // namespace ibfvs
