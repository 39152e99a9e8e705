// Critical points against exact answers (issue 64): on meshes jittered so
// that no answer falls on a vertex by construction, each point found within
// a small fraction of an edge with its kind, and the indices summing to the
// Euler characteristic (Poincare-Hopf).
#include "ibfvs/core/fields/topology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "core/fields/exact_fields.h"
#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

// Every vertex moved by up to a fifth of an edge, then back onto the surface.
using exact::jitter;
using exact::mean_edge;

glm::vec3 tangent(const glm::vec3& v, const glm::vec3& normal) {
  return v - glm::dot(v, normal) * normal;
}

// The points of one kind, sorted along an axis.
std::vector<CriticalPoint> of_kind(const CriticalPoints& c, CriticalKind kind) {
  std::vector<CriticalPoint> out;
  for (const CriticalPoint& p : c.points)
    if (p.kind == kind) out.push_back(p);
  return out;
}

void expect_near(const glm::vec3& got, const glm::vec3& want, double tolerance) {
  EXPECT_LT(glm::length(got - want), tolerance)
      << "at " << got.x << "," << got.y << "," << got.z << ", expected " << want.x << "," << want.y
      << "," << want.z;
}

TriMesh jittered_globe() {
  TriMesh m = make_globe(4);  // 5120 triangles
  jitter(
      m, [](glm::vec3 p) { return glm::normalize(p); }, 7);
  return m;
}

TEST(CriticalPoints, HeightOnASphereFlowsFromASourceToASink) {
  const TriMesh m = jittered_globe();
  const glm::vec3 up(0.3f, 0.2f, 0.932f);  // no vertex of the globe on the axis
  const glm::vec3 axis = glm::normalize(up);
  std::vector<glm::vec3> v;
  for (const glm::vec3& p : m.positions) v.push_back(tangent(axis, glm::normalize(p)));
  const CriticalPoints c = find_critical_points(m, v);
  ASSERT_EQ(c.points.size(), 2u);
  EXPECT_EQ(c.index_sum, euler_characteristic(m));
  EXPECT_EQ(euler_characteristic(m), 2);
  const double edge = mean_edge(m);
  const auto sink = of_kind(c, CriticalKind::AttractingNode);
  const auto source = of_kind(c, CriticalKind::RepellingNode);
  ASSERT_EQ(sink.size(), 1u);
  ASSERT_EQ(source.size(), 1u);
  expect_near(sink[0].position, axis, 0.1 * edge);
  expect_near(source[0].position, -axis, 0.1 * edge);
  EXPECT_LT(sink[0].eigen_real[1], 0.0);
  EXPECT_GT(source[0].eigen_real[0], 0.0);
}

TEST(CriticalPoints, ATurningAndASpiralOnASphere) {
  const TriMesh m = jittered_globe();
  const glm::vec3 axis = glm::normalize(glm::vec3(-0.2f, 0.95f, 0.25f));
  for (const float pull : {0.0f, 0.5f, -0.5f}) {
    std::vector<glm::vec3> v;
    for (const glm::vec3& p : m.positions) {
      const glm::vec3 n = glm::normalize(p);
      v.push_back(glm::cross(axis, n) + pull * tangent(axis, n));
    }
    const CriticalPoints c = find_critical_points(m, v);
    ASSERT_EQ(c.points.size(), 2u) << pull;
    EXPECT_EQ(c.index_sum, 2) << pull;
    const double edge = mean_edge(m);
    const CriticalKind at_axis = pull == 0.0f  ? CriticalKind::Centre
                                 : pull > 0.0f ? CriticalKind::AttractingFocus
                                               : CriticalKind::RepellingFocus;
    const CriticalKind opposite = pull == 0.0f  ? CriticalKind::Centre
                                  : pull > 0.0f ? CriticalKind::RepellingFocus
                                                : CriticalKind::AttractingFocus;
    for (const CriticalPoint& p : c.points) {
      const bool top = glm::dot(p.position, axis) > 0.0f;
      EXPECT_EQ(p.kind, top ? at_axis : opposite) << pull << ": " << kind_name(p.kind);
      expect_near(p.position, top ? axis : -axis, 0.1 * edge);
      EXPECT_NE(p.eigen_imag[1], 0.0);
    }
  }
}

TEST(CriticalPoints, HeightOnATorusHasTwoNodesAndTwoSaddles) {
  TriMesh m = make_torus(1.0f, 0.35f, 96, 48);  // axis +Y
  jitter(
      m,
      [](glm::vec3 p) {  // back onto the torus: the nearest point of it
        const glm::vec3 ring = glm::normalize(glm::vec3(p.x, 0.0f, p.z));
        return ring + 0.35f * glm::normalize(p - ring);
      },
      11);
  // The height along a direction in the torus's plane, a little off its
  // grid: its gradient on the surface.
  const glm::vec3 dir = glm::normalize(glm::vec3(1.0f, 0.0f, 0.137f));
  std::vector<glm::vec3> v;
  for (const glm::vec3& p : m.positions) {
    const glm::vec3 ring = glm::normalize(glm::vec3(p.x, 0.0f, p.z));
    v.push_back(tangent(dir, glm::normalize(p - ring)));
  }
  const CriticalPoints c = find_critical_points(m, v);
  EXPECT_EQ(euler_characteristic(m), 0);
  EXPECT_EQ(c.index_sum, 0);
  ASSERT_EQ(c.points.size(), 4u);
  const double edge = mean_edge(m);
  const auto saddles = of_kind(c, CriticalKind::Saddle);
  const auto sinks = of_kind(c, CriticalKind::AttractingNode);
  const auto sources = of_kind(c, CriticalKind::RepellingNode);
  ASSERT_EQ(saddles.size(), 2u);
  ASSERT_EQ(sinks.size(), 1u);
  ASSERT_EQ(sources.size(), 1u);
  expect_near(sinks[0].position, 1.35f * dir, 0.25 * edge);
  expect_near(sources[0].position, -1.35f * dir, 0.25 * edge);
  for (const CriticalPoint& s : saddles) {
    const glm::vec3 want = (glm::dot(s.position, dir) > 0.0f ? 0.65f : -0.65f) * dir;
    expect_near(s.position, want, 0.25 * edge);
    EXPECT_LT(s.eigen_real[0], 0.0);
    EXPECT_GT(s.eigen_real[1], 0.0);
  }
}

TEST(CriticalPoints, ZerosOnEdgesOfASymmetricMeshAreFoundOnce) {
  // Unjittered, the height along a direction in the torus's mirror plane
  // puts all four zeros on edges of the rings in that plane: each neighbour
  // finds them a little outside itself, as its own plane is tilted.
  const TriMesh m = make_torus(1.0f, 0.4f, 160, 64);
  const glm::vec3 up = glm::normalize(glm::vec3(1.0f, 0.0f, 0.137f));
  std::vector<glm::vec3> v;
  for (const glm::vec3& n : m.normals) v.push_back(tangent(up, n));
  const CriticalPoints c = find_critical_points(m, v);
  ASSERT_EQ(c.points.size(), 4u);
  EXPECT_EQ(c.index_sum, 0);
  EXPECT_EQ(of_kind(c, CriticalKind::Saddle).size(), 2u);
  EXPECT_EQ(c.degenerate_triangles, 0u);  // the top and bottom rings: constant, no zero
  for (const CriticalPoint& p : c.points)
    EXPECT_NEAR(std::abs(glm::dot(p.position, up)), p.kind == CriticalKind::Saddle ? 0.6 : 1.4,
                0.01);
}

TEST(CriticalPoints, BadInputIsAnErrorAndDegenerateTrianglesAreCounted) {
  TriMesh m = make_globe(1);
  std::vector<glm::vec3> v(m.positions.size(), glm::vec3(0.0f));
  const CriticalPoints zero = find_critical_points(m, v);
  EXPECT_TRUE(zero.points.empty());
  EXPECT_EQ(zero.zero_triangles, m.triangles.size());
  v[3].y = std::nanf("");
  EXPECT_THROW(find_critical_points(m, v), InputError);
  v.pop_back();
  EXPECT_THROW(find_critical_points(m, v), InputError);
  m.positions.push_back(m.positions[0]);  // a triangle with no area
  m.triangles.push_back({0, static_cast<std::uint32_t>(m.positions.size() - 1), 1});
  std::vector<glm::vec3> ok(m.positions.size(), glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_GE(find_critical_points(m, ok).degenerate_triangles, 1u);
}

// Rotation about `axis` with a pull of `k` towards (k > 0) or away from
// (k < 0) the great circle across it: the flow spirals out of the two poles
// onto that circle, a closed separation line (k < 0: the reverse, spiralling
// off an attachment line into the poles).
std::vector<glm::vec3> spiral_onto_circle(const TriMesh& m, const glm::vec3& axis, float k) {
  std::vector<glm::vec3> v;
  for (const glm::vec3& p : m.positions) {
    const glm::vec3 n = glm::normalize(p);
    const float z = glm::dot(axis, n);
    v.push_back(glm::cross(axis, n) - k * z * (axis - z * n));
  }
  return v;
}

// Where the lines of one kind lie, and how much of the circle across `axis`
// they cover (bins of 2 degrees of its angle).
struct Coverage {
  double farthest = 0.0;  // from the circle
  double covered = 0.0;   // fraction of the bins
  double length = 0.0;
};

Coverage coverage(const FeatureLines& lines, LineKind kind, const glm::vec3& axis) {
  const glm::vec3 a = glm::normalize(glm::cross(axis, glm::vec3(0.0f, 0.0f, 1.0f)));
  const glm::vec3 b = glm::cross(axis, a);
  std::vector<char> bins(180, 0);
  Coverage c;
  for (const FeatureLine& l : lines.lines) {
    if (l.kind != kind) continue;
    c.length += l.length;
    for (std::size_t i = 0; i < l.points.size(); ++i) {
      const glm::vec3 p = l.points[i].position;
      c.farthest = std::max(
          c.farthest, std::abs(std::asin(std::clamp(
                          static_cast<double>(glm::dot(glm::normalize(p), axis)), -1.0, 1.0))));
      // Bins between this point and the next (segments are short).
      const glm::vec3 q = l.points[(i + 1) % l.points.size()].position;
      if (i + 1 == l.points.size() && !l.closed) continue;
      double t0 = std::atan2(glm::dot(p, b), glm::dot(p, a)),
             t1 = std::atan2(glm::dot(q, b), glm::dot(q, a));
      if (t1 < t0) std::swap(t0, t1);
      if (t1 - t0 > 3.14159) continue;  // across the seam: a sliver left out
      for (double t = t0; t <= t1; t += 0.01)
        bins[static_cast<std::size_t>((t + 3.14159265) / (2 * 3.14159265) * 180) % 180] = 1;
    }
  }
  c.covered = std::count(bins.begin(), bins.end(), 1) / 180.0;
  return c;
}

TEST(FeatureLines, ASpiralOntoACircleIsAClosedSeparationLineAndItsReverseAnAttachmentLine) {
  const TriMesh m = jittered_globe();
  const double edge = mean_edge(m);
  const glm::vec3 axis = glm::normalize(glm::vec3(0.3f, 0.2f, 0.93f));
  for (const float k : {1.0f, -1.0f}) {
    const FeatureLines lines = find_topology(m, spiral_onto_circle(m, axis, k)).lines;
    const LineKind want = k > 0 ? LineKind::Separation : LineKind::Attachment;
    const LineKind other = k > 0 ? LineKind::Attachment : LineKind::Separation;
    const Coverage c = coverage(lines, want, axis);
    EXPECT_LT(c.farthest, 0.05 * edge) << k;  // radians on the unit sphere: arc length
    EXPECT_GT(c.covered, 0.97) << k;
    EXPECT_NEAR(c.length, 2 * 3.14159265, 0.1) << k;  // the circle, once
    EXPECT_EQ(coverage(lines, other, axis).length, 0.0) << k;
    ASSERT_EQ(lines.lines.size(), 1u) << k;
    EXPECT_TRUE(lines.lines[0].closed) << k;
    for (const FeatureLine& l : lines.lines) {
      EXPECT_EQ(l.kind, want);
      // Its neighbours converge onto it at the pull's rate 1 per unit of
      // length along it, so by e^(2 pi) a turn: the strength is 2 pi.
      EXPECT_NEAR(l.strength, 2.0 * 3.14159265, 0.1) << k;
      EXPECT_EQ(l.origin, LineOrigin::ClosedOrbit) << k;
    }
  }
}

TEST(FeatureLines, NoLinesInAFieldWithoutThem) {
  const TriMesh m = jittered_globe();
  const glm::vec3 axis = glm::normalize(glm::vec3(-0.2f, 0.95f, 0.25f));
  // A pure turning (closed orbits, nothing converges) and a zero field.
  EXPECT_TRUE(find_topology(m, spiral_onto_circle(m, axis, 0.0f)).lines.lines.empty());
  const std::vector<glm::vec3> zero(m.positions.size(), glm::vec3(0.0f));
  EXPECT_TRUE(find_topology(m, zero).lines.lines.empty());
}

}  // namespace
}  // namespace ibfvs
