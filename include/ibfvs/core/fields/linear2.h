#pragma once
// The linear algebra of a tangent field on one triangle, written once for the
// topology's every part (critical points, lines, the summary's strengths):
// the triangle's plane frame, the Jacobian of the field interpolated
// linearly over it, and the 2x2 eigen-decomposition that classifies it.

#include <array>
#include <optional>

#include <glm/vec3.hpp>

namespace ibfvs {

/// A 2x2 matrix [a b; c d] (row-major: a = m[0][0], b = m[0][1]).
struct Mat2 {
  double a = 0, b = 0, c = 0, d = 0;
  [[nodiscard]] double trace() const { return a + d; }
  [[nodiscard]] double det() const { return a * d - b * c; }
};

/// The eigenvalues of a 2x2 matrix, and its eigenvectors where they are
/// real: value[0] <= value[1] (real parts; imag[1] = -imag[0] >= 0 when
/// complex). vector[k] is a unit eigenvector of value[k] in the matrix's
/// coordinates (only where `real`).
struct Eigen2 {
  std::array<double, 2> value{}, imag{};
  std::array<std::array<double, 2>, 2> vector{};
  bool real = true;
  /// The largest absolute real part: a point's `strength`.
  [[nodiscard]] double largest_rate() const;
};
Eigen2 eigen2(const Mat2& m);

/// A triangle's plane: origin at its first corner, unit axes e1 (along its
/// first edge) and e2 = normal x e1.
struct TriangleFrame {
  glm::dvec3 origin{0.0}, e1{1, 0, 0}, e2{0, 1, 0}, normal{0, 0, 1};
  double area = 0.0;   ///< 0: degenerate (no frame)
  bool valid = false;  ///< area above the relative tolerance below
  [[nodiscard]] std::array<double, 2> of(const glm::dvec3& v) const;  ///< in-plane coordinates
  [[nodiscard]] glm::dvec3 at(double x, double y) const { return x * e1 + y * e2; }
};

/// The frame of the triangle (p0, p1, p2); invalid where its area is below
/// 1e-12 of its first edge squared (a sliver or a repeated corner).
TriangleFrame triangle_frame(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2);

/// The Jacobian of the field that interpolates w0, w1, w2 (at the corners
/// p0, p1, p2) linearly, each projected into the frame's plane, in the
/// frame's axes: J = M X^-1, M the vectors' differences and X the corners'.
Mat2 triangle_jacobian(const TriangleFrame& frame, const glm::dvec3& p1, const glm::dvec3& p2,
                       const glm::dvec3& w0, const glm::dvec3& w1, const glm::dvec3& w2);

}  // namespace ibfvs
