#pragma once
// A tangent vector field on a triangle mesh as the skin-friction topology
// reads it (topology.h), and the tracing of its field lines (skin-friction
// lines) across the triangles.
//
// The field is the mesh's per-vertex vectors less their part along each
// vertex's normal (the area-weighted mean of its triangles'). Two
// interpolations of it over a triangle serve two purposes:
//  - the vectors themselves, linearly: their zeros are the critical points
//    and their Jacobian classifies them (linear2.h);
//  - the vectors' directions (unit vectors, 0 where the vector is 0),
//    linearly: the field lines. A skin-friction line's path depends on the
//    field's direction only, so scaling each vertex's vector by a positive
//    factor of its own leaves every traced line exactly where it was; the
//    speed along it is what changes.
// A line is traced in arc length with classical Runge-Kutta steps inside each
// triangle (its corners' directions projected into its plane), stopping on
// the edge it leaves by and going on in the triangle across it.

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/fields/linear2.h"
#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

inline constexpr std::uint32_t kNoTriangle = 0xffffffffu;

/// A point on the surface: a triangle and a position in its plane.
struct SurfacePoint {
  std::uint32_t triangle = kNoTriangle;
  glm::dvec3 position{0.0};
};

class SurfaceField {
 public:
  /// Throws InputError (check_topology_input) for counts that differ or
  /// values that are not finite.
  SurfaceField(const TriMesh& mesh, std::span<const glm::vec3> vectors);

  [[nodiscard]] const TriMesh& mesh() const { return mesh_; }
  [[nodiscard]] std::size_t triangle_count() const { return frames_.size(); }

  // ---- per vertex
  [[nodiscard]] const glm::dvec3& normal(std::uint32_t v) const { return normal_[v]; }
  [[nodiscard]] const glm::dvec3& tangent(std::uint32_t v) const { return tangent_[v]; }
  [[nodiscard]] const glm::dvec3& direction(std::uint32_t v) const { return direction_[v]; }

  // ---- per triangle
  [[nodiscard]] const TriangleFrame& frame(std::uint32_t t) const { return frames_[t]; }
  /// The triangle across the edge from corner k to corner k+1, and that
  /// edge's index there; kNoTriangle on a boundary or non-manifold edge.
  [[nodiscard]] std::uint32_t neighbour(std::uint32_t t, int k) const { return across_[t][k]; }
  [[nodiscard]] int neighbour_edge(std::uint32_t t, int k) const { return across_edge_[t][k]; }
  /// The Jacobian of the linear field (in the frame's axes).
  [[nodiscard]] const Mat2& jacobian(std::uint32_t t) const { return jacobian_[t]; }
  /// The divergence of the linear direction field: the rate (per unit
  /// length along a line) at which neighbouring field lines spread apart
  /// (negative: they converge). Depends on directions only.
  [[nodiscard]] double direction_divergence(std::uint32_t t) const { return divergence_[t]; }
  /// The triangle's three corners' directions and vectors projected into its plane.
  [[nodiscard]] const std::array<glm::dvec3, 3>& corner_directions(std::uint32_t t) const {
    return corner_dir_[t];
  }

  // ---- at a point
  /// Barycentric coordinates of `p` (in the triangle's plane) in triangle t.
  [[nodiscard]] std::array<double, 3> barycentric(std::uint32_t t, const glm::dvec3& p) const;
  [[nodiscard]] glm::dvec3 field_at(const SurfacePoint& p) const;  ///< linear vectors
  [[nodiscard]] glm::dvec3 direction_at(
      const SurfacePoint& p) const;                                 ///< linear directions, not unit
  [[nodiscard]] glm::dvec3 normal_at(const SurfacePoint& p) const;  ///< interpolated, unit

  // ---- scales
  [[nodiscard]] double mean_edge() const { return mean_edge_; }
  /// The bounding box's diagonal of the triangles' corners.
  [[nodiscard]] double size() const { return size_; }
  /// That box's corners.
  [[nodiscard]] const glm::dvec3& lo() const { return lo_; }
  [[nodiscard]] const glm::dvec3& hi() const { return hi_; }

  /// The triangles around vertex v.
  [[nodiscard]] std::span<const std::uint32_t> fan(std::uint32_t v) const {
    return {fan_.data() + fan_start_[v], fan_start_[v + 1] - fan_start_[v]};
  }

 private:
  const TriMesh& mesh_;
  std::vector<glm::dvec3> normal_, tangent_, direction_;
  std::vector<TriangleFrame> frames_;
  // Per triangle: its corners 1 and 2 in its frame, and the inverse of
  // that 2x2's determinant (barycentric coordinates without recomputing it).
  struct Corners {
    double x1, y1, x2, y2, inv_det;
  };
  std::vector<Corners> corners_;
  std::vector<std::array<std::uint32_t, 3>> across_;
  std::vector<std::array<std::int8_t, 3>> across_edge_;
  std::vector<Mat2> jacobian_;
  std::vector<double> divergence_;
  std::vector<std::array<glm::dvec3, 3>> corner_dir_;
  std::vector<std::uint32_t> fan_, fan_start_;
  double mean_edge_ = 0.0, size_ = 0.0;
  glm::dvec3 lo_{0.0}, hi_{0.0};
};

/// One point of a traced line.
struct TracePoint {
  glm::dvec3 position{0.0};
  std::uint32_t triangle = kNoTriangle;
  double arc = 0.0;  ///< arc length from the start
};

/// Why a trace ended.
enum class TraceEnd {
  Length,     ///< it reached the length asked for
  Boundary,   ///< it left the surface across a boundary edge
  Stalled,    ///< the direction vanished (a zero of the field's directions)
  Converged,  ///< the flow on both sides of an edge points into it (a line of zeros)
  Stopped,    ///< the caller's visitor stopped it
};

struct Trace {
  std::vector<TracePoint> points;
  TraceEnd end = TraceEnd::Length;
};

/// Called with each new point (the first included); return false to stop.
using TraceVisitor = std::function<bool(const Trace& so_far)>;

/// Traces the field line through `start` along the field (`sense` +1) or
/// against it (-1) for at most `max_length`, in steps of at most `step`
/// (each also at most a quarter of its triangle's size).
Trace trace_line(const SurfaceField& field, const SurfacePoint& start, int sense, double max_length,
                 double step, const TraceVisitor& visit = {});

}  // namespace ibfvs
