#include <gtest/gtest.h>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/mesh/subdivision.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

TEST(Subdivision, CountsOnAClosedMesh) {
  const TriMesh t = make_torus(1.0f, 0.4f, 12, 8);  // closed: V - E + F = 0
  const std::size_t v = t.vertex_count(), f = t.triangle_count(), e = 3 * f / 2;
  const TriMesh s1 = loop_subdivide(t, 1);
  EXPECT_EQ(s1.triangle_count(), 4 * f);
  EXPECT_EQ(s1.vertex_count(), v + e);
  const TriMesh s2 = loop_subdivide(t, 2);
  EXPECT_EQ(s2.triangle_count(), 16 * f);
  EXPECT_EQ(s2.normals.size(), s2.vertex_count());
}

TEST(Subdivision, SmoothsTowardsTheLimitAndCarriesData) {
  TriMesh s = make_sphere(1.0f, 8, 16);
  s.vectors.assign(s.vertex_count(), glm::vec3(0.3f, -0.2f, 0.1f));
  s.scalars["height"].resize(s.vertex_count());
  for (std::size_t i = 0; i < s.vertex_count(); ++i) s.scalars["height"][i] = s.positions[i].y;
  const TriMesh r = loop_subdivide(s, 2);
  ASSERT_EQ(r.vectors.size(), r.vertex_count());
  ASSERT_EQ(r.scalars.at("height").size(), r.vertex_count());
  // Loop masks are affine: a constant field stays constant, a linear one follows y.
  for (std::size_t i = 0; i < r.vertex_count(); ++i) {
    EXPECT_NEAR(glm::length(r.vectors[i] - glm::vec3(0.3f, -0.2f, 0.1f)), 0.0f, 1e-5f);
    EXPECT_NEAR(r.scalars.at("height")[i], r.positions[i].y, 1e-5f);
  }
  // Loop shrinks a coarse sphere but every vertex stays between 0.8 and 1.
  for (const glm::vec3& p : r.positions) {
    EXPECT_LE(glm::length(p), 1.0001f);
    EXPECT_GT(glm::length(p), 0.8f);
  }
}

TEST(Subdivision, RejectsBadLevels) {
  const TriMesh t = make_square(1.0f, 1);
  EXPECT_THROW(loop_subdivide(t, -1), InputError);
  EXPECT_THROW(loop_subdivide(t, 13), InputError);
  EXPECT_THROW(loop_subdivide(make_square(1.0f, 64), 12), InputError);  // 137 billion triangles
  EXPECT_EQ(loop_subdivide(t, 0).triangle_count(), t.triangle_count());
}

}  // namespace
}  // namespace ibfvs

namespace ibfvs {
namespace {

TEST(Subdivision, ClosedStaysClosedAndTheIcosahedronApproachesASphere) {
  const TriMesh ico = make_icosahedron(1.0f);
  EXPECT_EQ(analyze_topology(ico).boundary_edges, 0u);
  double previous_move = 1e9;
  TriMesh previous = ico;
  for (int level = 1; level <= 4; ++level) {
    const TriMesh s = loop_subdivide(ico, level);
    const Topology top = analyze_topology(s);
    EXPECT_EQ(top.boundary_edges, 0u);
    EXPECT_EQ(top.nonmanifold_edges, 0u);
    EXPECT_EQ(s.triangle_count(), 20u << (2 * level));
    // Euler characteristic 2: V - E + F.
    EXPECT_EQ(static_cast<long>(s.vertex_count()) - static_cast<long>(top.edges) +
                  static_cast<long>(s.triangle_count()),
              2);
    float lo = 1e9f, hi = 0.0f;
    for (const glm::vec3& p : s.positions) {
      lo = std::min(lo, glm::length(p));
      hi = std::max(hi, glm::length(p));
    }
    // The limit surface of Loop on an icosahedron is close to a sphere.
    EXPECT_LT(hi - lo, 0.01f) << level;
    // Positions converge: the vertices of the previous level (which keep their
    // indices) move less and less from one level to the next.
    double move = 0.0;
    for (std::size_t i = 0; i < previous.vertex_count(); ++i)
      move =
          std::max(move, static_cast<double>(glm::length(s.positions[i] - previous.positions[i])));
    std::printf("loop level %d: radii %.4f..%.4f, old vertices moved %.2e\n", level, lo, hi, move);
    EXPECT_LT(move, 0.5 * previous_move) << level;
    previous_move = move;
    previous = s;
  }
}

TEST(Subdivision, NonManifoldFacesAreKept) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {0, 1, 2}};  // a third face on 0-1, a duplicate
  compute_vertex_normals(m);
  const TriMesh s = loop_subdivide(m, 1);
  EXPECT_EQ(s.triangle_count(), 16u);
  for (const glm::vec3& p : s.positions) EXPECT_TRUE(std::isfinite(p.x + p.y + p.z));
}

TEST(Topology, CountsBoundaryLoopsAndNonManifoldEdges) {
  const Topology sq = analyze_topology(make_square(1.0f, 3));
  EXPECT_EQ(sq.boundary_loops, 1u);
  EXPECT_EQ(sq.boundary_edges, 12u);
  const Topology cyl = analyze_topology(make_cylinder(1.0f, 1.0f, 12, 3));
  EXPECT_EQ(cyl.boundary_loops, 2u);
  TriMesh fan = make_square(1.0f, 1);
  fan.positions.emplace_back(0, 0, 5);
  fan.positions.emplace_back(7, 7, 7);  // isolated
  fan.triangles.push_back({0, 1, 4});   // third triangle on edge 0-1? no: 0-1 is a boundary edge
  fan.triangles.push_back({0, 1, 4});
  const Topology t = analyze_topology(fan);
  EXPECT_EQ(t.nonmanifold_edges, 1u);
  EXPECT_EQ(t.isolated_vertices, 1u);
}

}  // namespace
}  // namespace ibfvs
