#pragma once
// Procedural meshes built in code: the demo's fallback surface when the fetched
// data is missing, and the analytic surfaces the tests measure against.

#include <cstdint>
#include <vector>

#include "ibfvs/core/mesh/mesh.h"

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

/// A landscape (paper figure 2 and 7): the uniform cubic B-spline height
/// h(s, t) = sum_ij B_i(s) B_j(t) P_ij on a control grid of heights P
/// (row-major, `columns` x `rows`, at least 4 x 4), meshed with `resolution` x
/// `resolution` cells. The height is along +Y, the camera's up (the default
/// camera sees it edge-on, camera 0,90,0 from above), over x in [-1, 1]
/// (s) and z in [1, -1] (t), and is kept as the scalar "height". Throws InputError for a grid
/// smaller than 4 x 4 or a size mismatch.
TriMesh make_bspline_height_field(const std::vector<float>& controls, int columns, int rows,
                                  int resolution);

/// Control heights for make_bspline_height_field: uniform random in
/// [-amplitude, amplitude], deterministic for a seed.
std::vector<float> random_controls(int columns, int rows, float amplitude, std::uint32_t seed);

}  // namespace ibfvs
