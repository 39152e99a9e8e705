#pragma once
// The motion of a surface between two saved steps along its rigid motion,
// not along chords: each vertex's one-ring (the vertex and its neighbours
// in the triangles) is fitted with the rigid motion that maps it best from
// one step to the next (least squares; the rotation is the orthogonal
// factor of the polar decomposition of the cross-covariance, Kabsch 1976 /
// Horn 1987), written as a screw (Chasles: a turn about an axis and a slide
// along it). In between, the vertex turns about that axis by the fraction
// of the angle and takes the rest of its displacement (the slide and
// whatever is not rigid) linearly:
//
//   p(m) = p0 + (R(m theta) - I) l + m (p1 - p0 - (R(theta) - I) l)
//
// with the rotation vector omega = theta a (a the axis, radians) and the
// lever l = p0 - c from a point c on the axis. At m = 0 and 1 it gives the
// steps' own points exactly; a rigidly moving part stays rigid in between
// (a rotor keeps its size and a sliding interface stays closed, where the
// chord between a point's two positions cuts inside its circle); a
// deforming one blends its non-rigid remainder as the chord does. The GPU's
// vertex shader (render/glsl/ibfvs_vertex.glsl) evaluates the same
// formula; interpolate_position is its CPU reference.

#include <cstddef>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// Each vertex's screw from one step to the next: rotation vector (axis
/// times angle in radians, zero for a translation or where the fit is
/// undetermined) and lever (from a point on the axis to the vertex's first
/// position). Empty vectors: no motion to interpolate (chords).
struct SurfaceMotion {
  std::vector<glm::vec3> omega;
  std::vector<glm::vec3> lever;
  /// Vertices whose one-ring moved rigidly (its fit within 1e-4 of its
  /// size): the rest blend part of their motion linearly.
  std::size_t rigid = 0;
  [[nodiscard]] bool empty() const { return omega.empty(); }
};

/// The motion of each vertex of `triangles` from `from` to `to` (one point
/// per vertex each), fitted over its one-ring. A vertex in no triangle, or
/// whose one-ring is a line or a point, moves along its chord; so does one
/// that does not turn (less than 1e-6 radians). A turn of nearly half a
/// circle (over 179 degrees) in one step cannot tell its direction: those
/// vertices move along their chords too. Throws InputError for sizes that
/// differ or an index out of range.
SurfaceMotion fit_surface_motion(std::span<const Triangle> triangles,
                                 std::span<const glm::vec3> from, std::span<const glm::vec3> to);

/// A vertex's position at mix m in [0, 1] between its two steps (the
/// formula above); the chord where omega is zero.
glm::vec3 interpolate_position(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& omega,
                               const glm::vec3& lever, float m);

/// Its normal at mix m: the first step's turned by m theta, blended
/// towards the second's turned back by (1 - m) theta; unit length.
glm::vec3 interpolate_normal(const glm::vec3& n0, const glm::vec3& n1, const glm::vec3& omega,
                             float m);

/// v turned by the rotation vector `omega` (Rodrigues).
glm::vec3 rotate_by(const glm::vec3& v, const glm::vec3& omega);

/// Every vertex at mix m (the points interpolate_position gives), or the
/// chords where `motion` is empty.
std::vector<glm::vec3> surface_at(std::span<const glm::vec3> from, std::span<const glm::vec3> to,
                                  const SurfaceMotion& motion, float m);

}  // namespace ibfvs
