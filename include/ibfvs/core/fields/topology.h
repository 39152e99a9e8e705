#pragma once
// The topology of a tangent vector field on a triangle mesh (issue 64): its
// critical points, found and classified as Helman and Hesselink did for flow
// data ("Representation and display of vector field topology in fluid flow
// data sets", IEEE Computer 22(8):27-36, 1989): a critical point is a zero
// of the field, its kind given by the eigenvalues of the field's Jacobian
// there (saddle: real, opposite signs; node: real, one sign; focus:
// complex; centre: imaginary).
// On a surface, the field is the piecewise-linear one: on each triangle, the
// linear interpolation of its corners' vectors projected into the
// triangle's plane, which has at most one zero and a constant Jacobian. A
// zero inside a triangle (or on its edges or corners, counted once) is a
// critical point. On a closed surface their indices sum to the Euler
// characteristic (Poincare-Hopf), which the tests check.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// The kinds of issue 64's `kind` array (1-6: critical points).
enum class CriticalKind : int {
  saddle = 1,
  attracting_node = 2,
  repelling_node = 3,
  attracting_focus = 4,
  repelling_focus = 5,
  centre = 6,
};

/// The name of a kind ("saddle", "attracting node", ...).
const char* kind_name(CriticalKind kind);

struct CriticalPoint {
  glm::vec3 position{0.0f};
  std::size_t triangle = 0;  ///< the triangle it was found in
  CriticalKind kind = CriticalKind::saddle;
  int index = 1;  ///< Poincare index: -1 for a saddle, +1 otherwise
  /// The Jacobian's eigenvalues, real and imaginary parts (1/time in the
  /// field's units per the mesh's length).
  std::array<double, 2> eigen_real{}, eigen_imag{};
};

struct CriticalPoints {
  std::vector<CriticalPoint> points;
  int index_sum = 0;
  /// Triangles with no area, or whose linear field has no isolated zero
  /// (zero or constant along a line): left out and counted.
  std::size_t degenerate_triangles = 0;
  /// Triangles whose three corner vectors are all zero (no direction there).
  std::size_t zero_triangles = 0;
};

/// The critical points of `vectors` (one per vertex of `mesh`). Throws
/// InputError when the counts differ or a vector or position is not finite.
CriticalPoints find_critical_points(const TriMesh& mesh, std::span<const glm::vec3> vectors);

/// V - E + F of the mesh (edges counted once): 2 for a sphere, 0 for a torus.
long euler_characteristic(const TriMesh& mesh);

}  // namespace ibfvs
