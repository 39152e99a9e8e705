#include "ibfvs/core/fields/topology.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include <glm/geometric.hpp>

#include "ibfvs/core/fields/linear2.h"
#include "ibfvs/core/fields/surface_field.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

// Barycentric slack: a zero this close outside a triangle is on its edge,
// and found by the neighbour too; the copies are merged below (within
// kMerge of a mean edge). Each triangle projects the corners' vectors into
// its own plane, so on a curved surface a zero on an edge (where a symmetry
// plane puts it) lands a little outside both neighbours: 2e-4 of the edge on
// the torus of the tests, 32 triangles around.
constexpr double kOnEdge = 1e-3;
constexpr double kMerge = 4e-3;

struct Vec2 {
  double x = 0, y = 0;
};

// The distance from the origin to the triangle (a, b, c) in the plane.
double origin_distance(const Vec2& a, const Vec2& b, const Vec2& c) {
  const auto side = [](const Vec2& p, const Vec2& q) { return p.x * q.y - p.y * q.x; };
  const double s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
  if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return 0.0;
  const auto to_segment = [](const Vec2& p, const Vec2& q) {
    const double dx = q.x - p.x, dy = q.y - p.y, len2 = dx * dx + dy * dy;
    const double t = len2 > 0 ? std::clamp(-(p.x * dx + p.y * dy) / len2, 0.0, 1.0) : 0.0;
    return std::hypot(p.x + t * dx, p.y + t * dy);
  };
  return std::min({to_segment(a, b), to_segment(b, c), to_segment(c, a)});
}

void classify(const Mat2& j, CriticalPoint& p) {
  const Eigen2 e = eigen2(j);
  p.eigen_real = e.value;
  p.eigen_imag = e.imag;
  if (j.det() < 0.0) {
    p.kind = CriticalKind::Saddle;
    p.index = -1;
    return;
  }
  p.index = 1;
  if (e.real) {
    p.kind = j.trace() < 0.0 ? CriticalKind::AttractingNode : CriticalKind::RepellingNode;
    return;
  }
  // A centre where the spiralling is under a thousandth of the turning:
  // what the discrete field makes of a pure turning (1.6e-4 on the jittered
  // globe of the tests, its vectors tangent to the vertex normals).
  if (std::abs(e.value[0]) <= 1e-3 * e.imag[1])
    p.kind = CriticalKind::Centre;
  else
    p.kind = j.trace() < 0.0 ? CriticalKind::AttractingFocus : CriticalKind::RepellingFocus;
}

}  // namespace

std::span<const KindStyle> kind_styles() {
  static constexpr KindStyle kStyles[] = {
      {1, "saddle", {255, 221, 0}},
      {2, "attracting node", {0, 158, 115}},
      {3, "repelling node", {230, 97, 0}},
      {4, "attracting focus", {86, 180, 233}},
      {5, "repelling focus", {204, 121, 167}},
      {6, "centre", {255, 255, 255}},
      {10, "separation line", {220, 20, 30}},
      {11, "attachment line", {30, 90, 255}},
  };
  return kStyles;
}

std::array<unsigned char, 3> kind_colour(int kind) {
  for (const KindStyle& k : kind_styles())
    if (k.kind == kind) return k.rgb;
  return {255, 255, 255};
}

double CriticalPoint::strength() const {
  return std::max(std::abs(eigen_real[0]), std::abs(eigen_real[1]));
}

const char* kind_name(CriticalKind kind) {
  switch (kind) {
    case CriticalKind::Saddle:
      return "saddle";
    case CriticalKind::AttractingNode:
      return "attracting node";
    case CriticalKind::RepellingNode:
      return "repelling node";
    case CriticalKind::AttractingFocus:
      return "attracting focus";
    case CriticalKind::RepellingFocus:
      return "repelling focus";
    case CriticalKind::Centre:
      return "centre";
  }
  return "unknown";
}

long euler_characteristic(const TriMesh& mesh) {
  std::unordered_set<std::uint64_t> edges;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t a = t[k], b = t[(k + 1) % 3];
      edges.insert(std::min(a, b) << 32 | std::max(a, b));
    }
  return static_cast<long>(mesh.positions.size()) - static_cast<long>(edges.size()) +
         static_cast<long>(mesh.triangles.size());
}

void check_topology_input(const TriMesh& mesh, std::span<const glm::vec3> vectors) {
  if (vectors.size() != mesh.positions.size())
    throw InputError("topology: " + std::to_string(vectors.size()) + " vectors for " +
                     std::to_string(mesh.positions.size()) + " points");
  for (std::size_t i = 0; i < vectors.size(); ++i)
    if (!std::isfinite(vectors[i].x) || !std::isfinite(vectors[i].y) ||
        !std::isfinite(vectors[i].z) || !std::isfinite(mesh.positions[i].x) ||
        !std::isfinite(mesh.positions[i].y) || !std::isfinite(mesh.positions[i].z))
      throw InputError("topology: point " + std::to_string(i) +
                       " has a vector or a position that is not finite");
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (const std::uint32_t v : mesh.triangles[f])
      if (v >= mesh.positions.size())
        throw InputError("topology: triangle " + std::to_string(f) + " names a point out of range");
}

std::vector<glm::vec3> tangent_vectors(const TriMesh& mesh, std::span<const glm::vec3> vectors) {
  std::vector<glm::dvec3> normal(mesh.positions.size(), glm::dvec3(0.0));
  for (const Triangle& t : mesh.triangles) {
    const glm::dvec3 p0(mesh.positions[t[0]]);
    const glm::dvec3 n = glm::cross(glm::dvec3(mesh.positions[t[1]]) - p0,
                                    glm::dvec3(mesh.positions[t[2]]) - p0);  // area-weighted
    for (const std::uint32_t k : t) normal[k] += n;
  }
  std::vector<glm::vec3> out(vectors.begin(), vectors.end());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double len = glm::length(normal[i]);
    if (!(len > 0.0)) continue;
    const glm::dvec3 n = normal[i] / len, v(vectors[i]);
    out[i] = glm::vec3(v - glm::dot(v, n) * n);
  }
  return out;
}

CriticalPoints find_critical_points(const TriMesh& mesh, std::span<const glm::vec3> raw) {
  return find_critical_points(SurfaceField(mesh, raw));
}

CriticalPoints find_critical_points(const SurfaceField& field) {
  const TriMesh& mesh = field.mesh();
  CriticalPoints out;
  for (std::uint32_t f = 0; f < field.triangle_count(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const TriangleFrame& frame = field.frame(f);
    if (!frame.valid) {
      ++out.degenerate_triangles;
      continue;
    }
    const glm::dvec3 p0(mesh.positions[t[0]]), p1(mesh.positions[t[1]]), p2(mesh.positions[t[2]]);
    const glm::dvec3 u = p1 - p0, v = p2 - p0;
    const auto c0 = frame.of(field.tangent(t[0])), c1 = frame.of(field.tangent(t[1])),
               c2 = frame.of(field.tangent(t[2]));
    const Vec2 w0{c0[0], c0[1]}, w1{c1[0], c1[1]}, w2{c2[0], c2[1]};
    if (w0.x == 0 && w0.y == 0 && w1.x == 0 && w1.y == 0 && w2.x == 0 && w2.y == 0) {
      ++out.zero_triangles;
      continue;
    }
    // w(s, t) = w0 + s (w1 - w0) + t (w2 - w0) = 0
    const double m00 = w1.x - w0.x, m01 = w2.x - w0.x, m10 = w1.y - w0.y, m11 = w2.y - w0.y;
    const double det = m00 * m11 - m01 * m10;
    const double scale =
        std::max({std::hypot(w0.x, w0.y), std::hypot(w1.x, w1.y), std::hypot(w2.x, w2.y)});
    if (!(std::abs(det) > 1e-12 * scale * scale)) {
      // No isolated zero: a zero along a line or none at all (two corners
      // with one vector). Counted where the field vanishes in the triangle.
      if (scale > 0.0 && origin_distance(w0, w1, w2) <= 1e-6 * scale) ++out.degenerate_triangles;
      continue;
    }
    const double s = (-w0.x * m11 + w0.y * m01) / det;
    const double r = (-m00 * w0.y + m10 * w0.x) / det;
    const double b0 = 1.0 - s - r;
    if (s < -kOnEdge || r < -kOnEdge || b0 < -kOnEdge) continue;
    CriticalPoint p;
    p.triangle = f;
    p.normal = glm::vec3(frame.normal);
    p.position = glm::vec3(p0 + std::clamp(s, 0.0, 1.0) * u + std::clamp(r, 0.0, 1.0) * v);
    classify(field.jacobian(f), p);
    out.points.push_back(p);
  }
  // A zero on an edge or a corner is found by each triangle there: one kept
  // (neighbours looked up in a grid of cells as wide as the merge distance).
  const double merge = std::max(kMerge * field.mean_edge(), std::numeric_limits<double>::min());
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
  const auto cell = [&](const glm::vec3& p, int dx, int dy, int dz) {
    const auto c = [&](float x, int d) {
      const double k = std::clamp(std::floor(x / merge), -1e15, 1e15);  // no overflow
      return static_cast<std::uint64_t>(static_cast<std::int64_t>(k) + d) & 0x1fffff;
    };
    return c(p.x, dx) << 42 | c(p.y, dy) << 21 | c(p.z, dz);
  };
  std::vector<CriticalPoint> kept;
  for (const CriticalPoint& p : out.points) {
    bool near = false;
    for (int dx = -1; dx <= 1 && !near; ++dx)
      for (int dy = -1; dy <= 1 && !near; ++dy)
        for (int dz = -1; dz <= 1 && !near; ++dz) {
          const auto it = grid.find(cell(p.position, dx, dy, dz));
          if (it == grid.end()) continue;
          near = std::any_of(it->second.begin(), it->second.end(), [&](std::size_t k) {
            return glm::length(glm::dvec3(p.position - kept[k].position)) <= merge;
          });
        }
    if (near) continue;
    grid[cell(p.position, 0, 0, 0)].push_back(kept.size());
    kept.push_back(p);
  }
  out.points = std::move(kept);
  for (const CriticalPoint& p : out.points) out.index_sum += p.index;
  return out;
}

}  // namespace ibfvs
