#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibfvs/core/error.h"
#include "ibfvs/core/procedural.h"
#include "ibfvs/core/subdivision.h"

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
  EXPECT_THROW(loop_subdivide(t, 9), InputError);
  EXPECT_EQ(loop_subdivide(t, 0).triangle_count(), t.triangle_count());
}

}  // namespace
}  // namespace ibfvs
