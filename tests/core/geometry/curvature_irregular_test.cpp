// Curvature on irregular meshes against exact values (issue 18): jittered
// tori and ellipsoids, random triangulations of the sphere, Loop subdivision
// surfaces against their limit surface, noisy scans; side by side with
// CGAL's jet fitting where the build has CGAL.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibfvs/core/geometry/curvature.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "support/curvature_surfaces.h"

namespace ibfvs {
namespace {

using test::CurvatureErrors;
using test::TestSurface;

CurvatureErrors measure(const TestSurface& s, const Curvature& c, const char* label) {
  const CurvatureErrors e = test::curvature_errors(s, c);
  std::printf("%-48s %-14s kmax %.4f%% / %.4f%%  kmin %.6f  dir %.3f deg (%zu vertices)\n",
              s.name.c_str(), label, 100 * e.kmax_rel_median, 100 * e.kmax_rel_p95,
              e.kmin_abs_median, e.dir_median, e.count);
  EXPECT_EQ(e.non_finite, 0u);
  return e;
}

Curvature with_fit(const TriMesh& m, CurvatureFit fit) {
  CurvatureOptions o;
  o.fit = fit;
  return compute_curvature(m, o);
}

// The held-out torus: R = 1, r = 0.35, about 9K triangles, vertices
// moved along the surface by up to a third of an edge. Its figures for
// CGAL's jet fitting (degree 4, 2-ring) are the bar.
TEST(CurvatureIrregular, JitteredTorusReachesCgalsBestFigures) {
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    const TestSurface s = test::jittered_torus(1.0f, 0.35f, 113, 40, 1.0f / 3.0f, seed);
    const Curvature c = compute_curvature(s.mesh);
    EXPECT_EQ(c.fit, CurvatureFit::quartic);
    const CurvatureErrors e = measure(s, c, "automatic");
    EXPECT_LT(e.kmax_rel_median, 0.0006);  // measured 0.036%
    EXPECT_LT(e.kmax_rel_p95, 0.0030);     // measured 0.07%
    EXPECT_LT(e.kmin_abs_median, 0.0009);  // measured 0.00026
    EXPECT_LT(e.dir_median, 0.02);         // measured 0.000 degrees
  }
}

TEST(CurvatureIrregular, ErrorsFallAsTheJitteredMeshIsRefined) {
  double previous = std::numeric_limits<double>::infinity();
  for (const int segments : {57, 113, 226}) {
    const TestSurface s =
        test::jittered_torus(1.0f, 0.35f, segments, segments * 40 / 113, 1.0f / 3.0f, 7);
    const CurvatureErrors e = measure(s, compute_curvature(s.mesh), "automatic");
    // A quartic jet: the error falls as h^3, by 8 per halving; 4 leaves
    // room for the randomness of the jitter.
    EXPECT_LT(e.kmax_rel_median * 4.0, previous);
    previous = e.kmax_rel_median;
  }
}

TEST(CurvatureIrregular, JitteredEllipsoid) {
  const TestSurface s = test::jittered_ellipsoid({1.0f, 0.75f, 0.5f}, 4, 1.0f / 3.0f, 2);
  const CurvatureErrors e = measure(s, compute_curvature(s.mesh), "automatic");
  EXPECT_LT(e.kmax_rel_median, 0.0005);  // measured 0.010%
  EXPECT_LT(e.kmax_rel_p95, 0.003);      // measured 0.057%
  EXPECT_LT(e.kmin_abs_median, 0.0005);  // measured 0.00006
  EXPECT_LT(e.dir_median, 0.05);         // measured 0.000 degrees
}

TEST(CurvatureIrregular, RandomlyTriangulatedSphere) {
  if (!test::have_cgal()) GTEST_SKIP() << "built without CGAL (libcgal-dev)";
  const TestSurface s = test::random_sphere(1.0f, 3000, 3);
  const Curvature c = compute_curvature(s.mesh);
  const CurvatureErrors e = measure(s, c, "automatic");
  EXPECT_LT(e.kmax_rel_median, 0.0002);  // measured 0.002%
  EXPECT_LT(e.kmax_rel_p95, 0.001);      // measured 0.006%
  EXPECT_LT(e.kmin_abs_median, 0.0005);  // measured 0.00005
  // An umbilic everywhere: directions are arbitrary but well formed.
  for (std::size_t i = 0; i < s.mesh.vertex_count(); ++i) {
    ASSERT_NEAR(glm::dot(c.dmin[i], c.dmax[i]), 0.0f, 1e-4f);
    ASSERT_GT(glm::dot(glm::cross(c.dmax[i], c.dmin[i]), c.normal[i]), 0.99f);
  }
}

// The exact values of loop_limit_surface come from the control points; the
// limit surface itself, sampled 4 and 8 times finer, must pass through the
// predicted point and lie on the predicted paraboloid up to third-order
// terms: the misfit relative to the paraboloid halves with the distance.
// (Wrong masks leave a misfit that does not shrink.)
double paraboloid_misfit(const TestSurface& coarse, const TestSurface& fine, std::size_t& checked) {
  std::vector<std::vector<std::uint32_t>> ring(fine.mesh.vertex_count());
  for (const Triangle& t : fine.mesh.triangles)
    for (int k = 0; k < 3; ++k) ring[t[k]].push_back(t[(k + 1) % 3]);
  checked = 0;
  double worst = 0.0;
  for (std::size_t v = 0; v < coarse.mesh.vertex_count(); ++v) {
    if (!coarse.known[v]) continue;
    const glm::dvec3 p(coarse.mesh.positions[v]);
    // Old vertices keep their index through Loop subdivision.
    EXPECT_LT(glm::length(glm::dvec3(fine.mesh.positions[v]) - p), 1e-5) << v;
    const glm::dvec3 dmax(coarse.dmax[v]), dmin(coarse.dmin[v]);
    const glm::dvec3 n = glm::cross(dmax, dmin);
    double scale = 0.0, err = 0.0;
    for (const std::uint32_t w : ring[v]) {
      const glm::dvec3 d = glm::dvec3(fine.mesh.positions[w]) - p;
      const double x = glm::dot(d, dmax), y = glm::dot(d, dmin), z = glm::dot(d, n);
      const double predicted = -0.5 * (coarse.kmax[v] * x * x + coarse.kmin[v] * y * y);
      scale = std::max(scale, std::abs(predicted));
      err = std::max(err, std::abs(z - predicted));
    }
    worst = std::max(worst, err / scale);
    ++checked;
  }
  return worst;
}

TEST(CurvatureIrregular, LoopLimitValuesDescribeTheLimitSurface) {
  if (!test::have_cgal()) GTEST_SKIP() << "built without CGAL (libcgal-dev)";
  const TriMesh coarse = test::random_sphere(1.0f, 60, 4).mesh;
  const TestSurface s2 = test::loop_limit_surface(coarse, 2, "level 2");
  std::size_t checked4 = 0, checked5 = 0;
  const double at4 = paraboloid_misfit(s2, test::loop_limit_surface(coarse, 4, "4"), checked4);
  const double at5 = paraboloid_misfit(s2, test::loop_limit_surface(coarse, 5, "5"), checked5);
  std::printf(
      "%zu regular vertices: the limit surface a quarter and an eighth of an edge away is "
      "within %.1f%% and %.1f%% of the predicted paraboloid\n",
      checked4, 100 * at4, 100 * at5);
  EXPECT_GT(checked4, 40u);
  EXPECT_LT(at5, 0.1);
  EXPECT_LT(at5, 0.6 * at4);
}

TEST(CurvatureIrregular, LoopLimitSurfaces) {
  if (!test::have_cgal()) GTEST_SKIP() << "built without CGAL (libcgal-dev)";
  const TestSurface s =
      test::loop_limit_surface(test::random_sphere(1.0f, 60, 4).mesh, 3, "Loop limit, random hull");
  const CurvatureErrors e = measure(s, compute_curvature(s.mesh), "automatic");
  // The limit surface is C2 only (piecewise quartic): errors are larger.
  EXPECT_LT(e.kmax_rel_median, 0.005);  // measured 0.23%
  EXPECT_LT(e.kmax_rel_p95, 0.04);      // measured 2.2%
  EXPECT_LT(e.dir_median, 0.4);         // measured 0.16 degrees
}

TEST(CurvatureIrregular, ScannedMeshAgainstItsLoopLimitSurface) {
  const std::filesystem::path p = std::filesystem::path(IBFVS_TEST_DATA_DIR) / "meshes/cow.off";
  if (!std::filesystem::exists(p)) GTEST_SKIP() << "fetched data missing: " << p;
  const TestSurface s = test::loop_limit_surface(read_mesh(p), 2, "Loop limit of the cow");
  const Curvature c = compute_curvature(s.mesh);
  EXPECT_EQ(c.fit, CurvatureFit::quartic);
  const CurvatureErrors e = measure(s, c, "automatic");
  EXPECT_LT(e.kmax_rel_median, 0.008);  // measured 0.44%
  EXPECT_LT(e.kmax_rel_p95, 0.08);      // measured 5.1%
  EXPECT_LT(e.dir_median, 0.5);         // measured 0.30 degrees
  if (test::have_cgal()) {
    const CurvatureErrors cgal = measure(s, test::cgal_jet_fitting(s.mesh, 4, 2), "CGAL d4");
    EXPECT_LT(e.kmax_rel_median, cgal.kmax_rel_median);
    EXPECT_LT(e.dir_median, cgal.dir_median);
  }
}

// On every irregular surface, ibfvs's default is at least as accurate as
// CGAL's jet fitting of degree 4 on the 2-ring, on the same mesh.
TEST(CurvatureIrregular, AtLeastAsAccurateAsCgalJetFitting) {
  if (!test::have_cgal()) GTEST_SKIP() << "built without CGAL (libcgal-dev)";
  const TestSurface surfaces[] = {
      test::jittered_torus(1.0f, 0.35f, 113, 40, 1.0f / 3.0f, 1),
      test::jittered_ellipsoid({1.0f, 0.75f, 0.5f}, 4, 1.0f / 3.0f, 2),
      test::random_sphere(1.0f, 3000, 3),
      test::loop_limit_surface(test::random_sphere(1.0f, 60, 4).mesh, 3, "Loop limit, random hull"),
  };
  for (const TestSurface& s : surfaces) {
    SCOPED_TRACE(s.name);
    const CurvatureErrors ours = measure(s, compute_curvature(s.mesh), "automatic");
    const CurvatureErrors cgal = measure(s, test::cgal_jet_fitting(s.mesh, 4, 2), "CGAL d4");
    EXPECT_LE(ours.kmax_rel_median, cgal.kmax_rel_median * 1.001);
    EXPECT_LE(ours.kmax_rel_p95, cgal.kmax_rel_p95 * 1.001);
    EXPECT_LE(ours.kmin_abs_median, cgal.kmin_abs_median * 1.001);
    EXPECT_LE(ours.dir_median, cgal.dir_median + 1e-3);
  }
}

// A scan's noise: a quartic follows it, so the automatic choice takes the
// cubic fit with normals, and its errors stay those of the cubic.
TEST(CurvatureIrregular, NoisyMeshesGetTheCubicFitWithNormals) {
  TestSurface s = test::jittered_torus(1.0f, 0.35f, 113, 40, 1.0f / 3.0f, 1);
  test::add_normal_noise(s, 0.01f, 5);
  const Curvature automatic = compute_curvature(s.mesh);
  EXPECT_EQ(automatic.fit, CurvatureFit::cubic_with_normals);
  EXPECT_EQ(automatic.quartic_vertices, 0u);
  const CurvatureErrors e = measure(s, automatic, "automatic");
  const CurvatureErrors q = measure(s, with_fit(s.mesh, CurvatureFit::quartic), "quartic");
  EXPECT_LT(e.kmax_rel_median, 0.05);  // measured 3.8%; the quartic 18%
  EXPECT_LT(e.dir_median, 1.0);        // measured 0.57 degrees; the quartic 6.6
  EXPECT_LT(e.kmax_rel_median * 3, q.kmax_rel_median);
  EXPECT_LT(e.dir_median * 3, q.dir_median);
  // Without noise the same mesh is exact: the quartic.
  const TestSurface clean = test::jittered_torus(1.0f, 0.35f, 113, 40, 1.0f / 3.0f, 1);
  const Curvature exact = compute_curvature(clean.mesh);
  EXPECT_EQ(exact.fit, CurvatureFit::quartic);
  EXPECT_GT(exact.noise_ratio, 10.0f);
  EXPECT_LT(automatic.noise_ratio, 4.0f);
}

// A seam whose vertices are not welded: each side fits what it sees (a
// boundary), no NaN, and the curvature stays close.
TEST(CurvatureIrregular, UnweldedSeamAndBoundaries) {
  TestSurface s = test::jittered_torus(1.0f, 0.35f, 113, 40, 1.0f / 3.0f, 1);
  const int segments = 113, sides = 40;
  // Give column 0 a copy of its vertices for the triangles on its left.
  const std::size_t n = s.mesh.vertex_count();
  std::vector<std::uint32_t> copy(n, 0);
  for (int j = 0; j < sides; ++j) {
    const std::size_t k = static_cast<std::size_t>(j) * segments;
    copy[k] = static_cast<std::uint32_t>(s.mesh.positions.size());
    s.mesh.positions.push_back(s.mesh.positions[k]);
    s.mesh.normals.push_back(s.mesh.normals[k]);
    s.kmin.push_back(s.kmin[k]), s.kmax.push_back(s.kmax[k]);
    s.dmin.push_back(s.dmin[k]), s.dmax.push_back(s.dmax[k]), s.known.push_back(1);
  }
  for (Triangle& t : s.mesh.triangles) {
    bool touches_last = false;
    for (const std::uint32_t v : t) touches_last |= v % segments == segments - 1;
    if (touches_last)
      for (std::uint32_t& v : t)
        if (v % segments == 0) v = copy[v];
  }
  compute_vertex_normals(s.mesh);
  const Curvature c = compute_curvature(s.mesh);
  const CurvatureErrors e = measure(s, c, "automatic");
  EXPECT_LT(e.kmax_rel_median, 0.001);
  EXPECT_LT(e.kmax_rel_p95, 0.05);
  for (std::size_t i = 0; i < s.mesh.vertex_count(); ++i) {
    ASSERT_TRUE(std::isfinite(c.kmin[i]) && std::isfinite(c.kmax[i])) << i;
    ASSERT_NEAR(glm::length(c.normal[i]), 1.0f, 1e-4f) << i;
  }
}

TEST(CurvatureIrregular, NonFiniteAndCollinearInputGiveNoNaN) {
  TestSurface s = test::jittered_torus(1.0f, 0.35f, 40, 14, 1.0f / 3.0f, 1);
  s.mesh.positions[17] = glm::vec3(std::numeric_limits<float>::quiet_NaN());
  s.mesh.positions[200] = glm::vec3(std::numeric_limits<float>::infinity());
  compute_vertex_normals(s.mesh);
  s.mesh.normals[300] = glm::vec3(0);
  // A fan of collinear points: its own neighbourhood spans no surface.
  TriMesh line;
  for (int i = 0; i < 6; ++i) line.positions.emplace_back(static_cast<float>(i), 0.0f, 0.0f);
  line.triangles = {{0, 1, 2}, {1, 2, 3}, {2, 3, 4}, {3, 4, 5}};
  compute_vertex_normals(line);
  for (const TriMesh* m : {&s.mesh, &line})
    for (const CurvatureFit fit :
         {CurvatureFit::automatic, CurvatureFit::quartic, CurvatureFit::cubic_with_normals}) {
      const Curvature c = with_fit(*m, fit);
      for (std::size_t i = 0; i < m->vertex_count(); ++i) {
        ASSERT_TRUE(std::isfinite(c.kmin[i]) && std::isfinite(c.kmax[i])) << i;
        for (const glm::vec3& d : {c.dmin[i], c.dmax[i], c.normal[i]})
          ASSERT_TRUE(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z)) << i;
      }
    }
}

}  // namespace
}  // namespace ibfvs
