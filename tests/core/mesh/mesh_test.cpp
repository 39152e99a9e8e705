#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs {
namespace {

TEST(Mesh, ComputedNormalsMatchTheSphere) {
  TriMesh m = make_sphere(2.0f, 32, 64);
  const std::vector<glm::vec3> exact = m.normals;
  compute_vertex_normals(m);
  float worst = 1.0f;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    const float y = exact[i].y;
    if (std::abs(y) > 0.99f) continue;  // the collapsed pole rows
    worst = std::min(worst, glm::dot(m.normals[i], exact[i]));
  }
  EXPECT_GT(worst, 0.995f);
}

TEST(Mesh, NormalsAreTheAngleWeightedOnes) {
  // A mesh whose corners span every angle (a fan about a cone's apex, of
  // unequal sectors, and their rims): the normals equal the mean of the
  // triangles' normals weighted by exact corner angles.
  TriMesh m;
  m.positions.push_back({0.0f, 0.0f, 0.6f});
  constexpr int kSectors = 9;
  float angle = 0.0f;
  for (int k = 0; k < kSectors; ++k) {
    m.positions.push_back({std::cos(angle), std::sin(angle), 0.1f * static_cast<float>(k % 3)});
    angle += 0.25f + 0.9f * static_cast<float>(k) / kSectors;  // 14 to 63 degrees
  }
  for (std::uint32_t k = 1; k < kSectors; ++k) m.triangles.push_back({0, k, k + 1});
  m.triangles.push_back({1, 4, 7});  // a wide triangle under the fan
  std::vector<glm::dvec3> exact(m.positions.size(), glm::dvec3(0.0)), even = exact;
  for (const Triangle& t : m.triangles) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(
        glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]])));
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 a = m.positions[t[(k + 1) % 3]] - m.positions[t[k]];
      const glm::dvec3 b = m.positions[t[(k + 2) % 3]] - m.positions[t[k]];
      exact[t[k]] += std::acos(glm::dot(glm::normalize(a), glm::normalize(b))) * n;
      even[t[k]] += n;
    }
  }
  const auto apart = [](glm::dvec3 a, glm::dvec3 b) {  // radians
    return glm::length(glm::cross(glm::normalize(a), glm::normalize(b)));
  };
  compute_vertex_normals(m);
  double worst = 0.0, weights = 0.0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    worst = std::max(worst, apart(m.normals[i], exact[i]));
    weights = std::max(weights, apart(even[i], exact[i]));
  }
  std::printf("normals %.2g radians off the angle-weighted ones (unweighted: %.2g)\n", worst,
              weights);
  // Measured: 7.3e-6 (std::acos: 0); unweighted 0.14.
  EXPECT_LT(worst, 2e-4);
  EXPECT_GT(weights, 100 * 2e-4);
}

// Pieces joined (ParaView's ranks' pieces for a page): triangles renumbered,
// every array one per vertex, an array one piece lacks dropped.
TEST(Mesh, AppendedPiecesKeepTheArraysBothHave) {
  TriMesh a = make_square(1.0f, 2), b = make_sphere(1.0f, 4, 8);
  a.vectors.assign(a.vertex_count(), glm::vec3(1, 0, 0));
  b.vectors.assign(b.vertex_count(), glm::vec3(0, 1, 0));
  a.scalars["t"].assign(a.vertex_count(), 0.25f);
  b.scalars["t"].assign(b.vertex_count(), 0.75f);
  a.scalars["only a"].assign(a.vertex_count(), 1.0f);
  b.vector_arrays["only b"].assign(b.vertex_count(), glm::vec3(1.0f));
  b.normals.clear();  // b lacks normals
  TriMesh joined;
  append_mesh(joined, a);
  EXPECT_EQ(joined.normals, a.normals);  // the first piece's arrays, all of them
  EXPECT_EQ(joined.scalars.count("only a"), 1u);
  append_mesh(joined, b);
  const std::size_t n = a.vertex_count() + b.vertex_count();
  ASSERT_EQ(joined.vertex_count(), n);
  ASSERT_EQ(joined.triangle_count(), a.triangle_count() + b.triangle_count());
  EXPECT_EQ(joined.triangles[a.triangle_count()][1], b.triangles[0][1] + a.vertex_count());
  EXPECT_NO_THROW(validate_mesh(joined, "joined"));
  EXPECT_TRUE(joined.normals.empty());
  ASSERT_EQ(joined.vectors.size(), n);
  EXPECT_EQ(joined.vectors.back(), glm::vec3(0, 1, 0));
  ASSERT_EQ(joined.scalars.size(), 1u);
  EXPECT_FLOAT_EQ(joined.scalars["t"][0], 0.25f);
  EXPECT_FLOAT_EQ(joined.scalars["t"][n - 1], 0.75f);
  EXPECT_TRUE(joined.vector_arrays.empty());
}

TEST(Mesh, TopologyHashTellsTrianglesApart) {
  const TriMesh m = make_torus(1.0f, 0.4f, 24, 12);
  const std::uint64_t h = topology_hash(m);
  TriMesh moved = m;
  for (glm::vec3& p : moved.positions) p += glm::vec3(0.5f);
  EXPECT_EQ(topology_hash(moved), h);  // points do not count
  TriMesh swapped = m;
  std::swap(swapped.triangles[3], swapped.triangles[4]);
  TriMesh turned = m;
  std::rotate(turned.triangles[7].begin(), turned.triangles[7].begin() + 1,
              turned.triangles[7].end());
  TriMesh fewer = m;
  fewer.triangles.pop_back();
  TriMesh more_points = m;
  more_points.positions.push_back(glm::vec3(0.0f));
  for (const TriMesh* other : {&swapped, &turned, &fewer, &more_points})
    EXPECT_NE(topology_hash(*other), h);
}

// The same points with other triangles (every quadrilateral of a grid
// split along its other diagonal) correspond; the same number of points
// numbered otherwise, or another number, do not.
TEST(Mesh, PointsCorrespondWhereMostEdgesStay) {
  const auto grid = [](bool flipped, bool renumbered) {
    TriMesh m;
    constexpr std::uint32_t n = 8;
    for (std::uint32_t y = 0; y <= n; ++y)
      for (std::uint32_t x = 0; x <= n; ++x) m.positions.emplace_back(x, y, 0.0f);
    const auto at = [&](std::uint32_t x, std::uint32_t y) {
      const std::uint32_t i = y * (n + 1) + x;
      return renumbered ? (i * 37) % ((n + 1) * (n + 1)) : i;  // 37 is prime to 81
    };
    for (std::uint32_t y = 0; y < n; ++y)
      for (std::uint32_t x = 0; x < n; ++x) {
        if (flipped) {
          m.triangles.push_back({at(x, y), at(x + 1, y), at(x, y + 1)});
          m.triangles.push_back({at(x + 1, y), at(x + 1, y + 1), at(x, y + 1)});
        } else {
          m.triangles.push_back({at(x, y), at(x + 1, y), at(x + 1, y + 1)});
          m.triangles.push_back({at(x, y), at(x + 1, y + 1), at(x, y + 1)});
        }
      }
    return m;
  };
  const TriMesh a = grid(false, false);
  EXPECT_TRUE(points_correspond(a, a));
  EXPECT_TRUE(points_correspond(a, grid(true, false)));
  EXPECT_FALSE(points_correspond(a, grid(false, true)));
  TriMesh more = a;
  more.positions.emplace_back(0.0f);
  EXPECT_FALSE(points_correspond(a, more));
}

TEST(Mesh, BoundsAndRadius) {
  const TriMesh m = make_torus(1.0f, 0.25f, 64, 16);
  const Bounds b = mesh_bounds(m);
  EXPECT_NEAR(b.max.x, 1.25f, 1e-5f);
  EXPECT_NEAR(b.max.y, 0.25f, 1e-5f);
  EXPECT_NEAR(b.radius, 1.25f, 1e-4f);
  EXPECT_LT(b.radius, 0.5f * b.diagonal());
}

TEST(Mesh, ValidateNamesTheProblem) {
  TriMesh m = make_square(1.0f, 1);
  m.triangles.push_back({0, 1, 17});
  try {
    validate_mesh(m, "in.off");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("in.off: triangle 2 references vertex 17"),
              std::string::npos)
        << e.what();
  }
  TriMesh empty;
  EXPECT_THROW(validate_mesh(empty, "x"), InputError);
  EXPECT_THROW(mesh_bounds(empty), InputError);
}

TEST(Mesh, DegenerateTrianglesAreRemovedAndNormalsStayFinite) {
  TriMesh m = make_square(1.0f, 1);
  m.triangles.push_back({0, 0, 1});
  m.positions.push_back(m.positions[0]);  // a copy of vertex 0: zero-area triangle
  m.triangles.push_back({0, 4, 1});
  compute_vertex_normals(m);
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
  EXPECT_EQ(remove_degenerate_triangles(m), 2u);
  EXPECT_EQ(m.triangle_count(), 2u);
}

TEST(Mesh, ClosedOrientationSaysWhenBackFacesCanBeCulled) {
  const TriMesh torus = make_torus(1.0f, 0.4f, 24, 12);
  EXPECT_EQ(closed_orientation(torus), 1);
  TriMesh inside_out = torus;
  for (Triangle& t : inside_out.triangles) std::swap(t[1], t[2]);
  EXPECT_EQ(closed_orientation(inside_out), -1);
  EXPECT_EQ(closed_orientation(make_square(1.0f, 4)), 0);             // open
  EXPECT_EQ(closed_orientation(make_cylinder(1.0f, 1.0f, 8, 2)), 0);  // open ends
  TriMesh mixed = torus;
  std::swap(mixed.triangles[5][1], mixed.triangles[5][2]);  // one flipped triangle
  EXPECT_EQ(closed_orientation(mixed), 0);
  EXPECT_EQ(closed_orientation(TriMesh{}), 0);
}

}  // namespace
}  // namespace ibfvs

namespace ibfvs {
namespace {

TEST(Mesh, TriangleValuesReachTheVerticesAreaWeighted) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2, 0}, {9, 9, 9}};
  m.triangles = {{0, 1, 2}, {1, 3, 2}};  // areas 0.5 and 1.5; vertex 4 of none
  const std::vector<float> v = triangle_to_vertex(m, std::vector<float>{1, 5});
  EXPECT_FLOAT_EQ(v[0], 1.0f);
  EXPECT_FLOAT_EQ(v[1], 4.0f);
  EXPECT_FLOAT_EQ(v[3], 5.0f);
  EXPECT_FLOAT_EQ(v[4], 0.0f);
  EXPECT_THROW(triangle_to_vertex(m, std::vector<float>{1}), InputError);
}

TEST(Text, GlobMatch) {
  EXPECT_TRUE(glob_match("motorBike*", "motorBike_frt-fairing:001%1"));
  EXPECT_TRUE(glob_match("*wing?", "leftwing2"));
  EXPECT_TRUE(glob_match("*", ""));
  EXPECT_FALSE(glob_match("wing", "wings"));
  EXPECT_FALSE(glob_match("a*b*c", "aXbY"));
  EXPECT_TRUE(glob_match("a*b*c", "aXbYc"));
}

}  // namespace
}  // namespace ibfvs
