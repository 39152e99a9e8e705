#include <array>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "ibfvs/core/mesh/gpu_prep.h"
#include "ibfvs/core/mesh/procedural.h"

namespace ibfvs {
namespace {

// The set of triangles as position triples, independent of vertex order.
std::multiset<std::array<float, 9>> triangle_set(const TriMesh& m) {
  std::multiset<std::array<float, 9>> out;
  for (const Triangle& t : m.triangles) {
    std::array<float, 9> a{};
    // Rotate so the smallest index... by position: keep winding, start anywhere.
    int first = 0;
    for (int k = 1; k < 3; ++k) {
      const glm::vec3 &p = m.positions[t[k]], &q = m.positions[t[first]];
      if (std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z)) first = k;
    }
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& p = m.positions[t[(first + k) % 3]];
      a[3 * k] = p.x, a[3 * k + 1] = p.y, a[3 * k + 2] = p.z;
    }
    out.insert(a);
  }
  return out;
}

TEST(GpuPrep, ImprovesTheVertexCacheAndKeepsTheSurface) {
  TriMesh m = make_torus(1.0f, 0.3f, 200, 60);
  // Shuffle the triangles so that the input order is poor.
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    std::swap(m.triangles[i], m.triangles[(i * 7919) % m.triangles.size()]);
  m.vectors = m.positions;  // a field that must move with its vertices
  m.scalars["y"].resize(m.vertex_count());
  for (std::size_t i = 0; i < m.vertex_count(); ++i) m.scalars["y"][i] = m.positions[i].y;
  const auto before = triangle_set(m);
  const float acmr_before = vertex_cache_acmr(m);
  optimize_for_gpu(m);
  const float acmr_after = vertex_cache_acmr(m);
  std::printf("ACMR %.3f -> %.3f\n", acmr_before, acmr_after);
  EXPECT_LT(acmr_after, 0.8f);
  EXPECT_LT(acmr_after, 0.5f * acmr_before);
  EXPECT_EQ(triangle_set(m), before);
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    EXPECT_EQ(m.vectors[i], m.positions[i]);
    EXPECT_EQ(m.scalars["y"][i], m.positions[i].y);
  }
}

TEST(GpuPrep, DropsUnreferencedVertices) {
  TriMesh m = make_square(1.0f, 2);
  m.positions.emplace_back(9, 9, 9);
  m.normals.emplace_back(0, 0, 1);
  optimize_for_gpu(m);
  EXPECT_EQ(m.vertex_count(), 9u);
  EXPECT_EQ(m.normals.size(), 9u);
}

}  // namespace
}  // namespace ibfvs
