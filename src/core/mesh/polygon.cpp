#include "ibfvs/core/mesh/polygon.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace ibfvs {

namespace {

double cross2(const glm::dvec2& a, const glm::dvec2& b) {
  return a.x * b.y - a.y * b.x;
}

// Whether q lies inside the triangle abc (counter-clockwise) or on its edges.
bool inside(const glm::dvec2& q, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return cross2(b - a, q - a) >= 0.0 && cross2(c - b, q - b) >= 0.0 && cross2(a - c, q - c) >= 0.0;
}

constexpr double kStraight = 1e-4;  // sine of a corner's turn taken as no turn
// Ear clipping takes up to n^3 steps: a polygon larger than this (no
// solver's face; a malicious file's) is fanned, in bounded time.
constexpr std::size_t kMostClipped = 1024;

}  // namespace

std::vector<Triangle> triangulate_polygon(std::span<const std::uint32_t> ids,
                                          std::span<const glm::vec3> points) {
  const std::size_t n = ids.size();
  std::vector<Triangle> out;
  if (n < 3) return out;
  out.reserve(n - 2);
  const auto fan = [&](const std::vector<std::size_t>& left) {
    for (std::size_t k = 1; k + 1 < left.size(); ++k)
      out.push_back({ids[left[0]], ids[left[k]], ids[left[k + 1]]});
  };
  std::vector<std::size_t> left(n);
  for (std::size_t k = 0; k < n; ++k) left[k] = k;
  if (n == 3) {
    fan(left);
    return out;
  }
  // The polygon seen along its mean (Newell) normal, about its first point.
  glm::dvec3 normal(0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const glm::dvec3 a(points[ids[k]]), b(points[ids[(k + 1) % n]]);
    normal += glm::cross(a, b);
  }
  const double length = glm::length(normal);
  if (!(length > 0.0)) {  // no area: any triangles are as good
    fan(left);
    return out;
  }
  normal /= length;
  const glm::dvec3 u = glm::normalize(std::abs(normal.x) < 0.9 ? glm::cross(normal, {1, 0, 0})
                                                               : glm::cross(normal, {0, 1, 0}));
  const glm::dvec3 v = glm::cross(normal, u);
  const glm::dvec3 origin(points[ids[0]]);
  std::vector<glm::dvec2> p(n);
  for (std::size_t k = 0; k < n; ++k) {
    const glm::dvec3 d = glm::dvec3(points[ids[k]]) - origin;
    p[k] = {glm::dot(d, u), glm::dot(d, v)};
  }
  // A corner turns the polygon's way (counter-clockwise about the normal),
  // or back by less than kStraight of its two edges.
  const auto turns = [&](std::size_t a, std::size_t b, std::size_t c, double slack) {
    const glm::dvec2 e1 = p[b] - p[a], e2 = p[c] - p[b];
    return cross2(e1, e2) >= -slack * glm::length(e1) * glm::length(e2);
  };
  bool convex = true;
  for (std::size_t k = 0; k < n && convex; ++k)
    convex = turns(k, (k + 1) % n, (k + 2) % n, kStraight);
  if (convex || n > kMostClipped) {
    fan(left);
    return out;
  }
  // Ear clipping in the polygon's order: the ear at left[i] is its corner
  // with the neighbours, turning the polygon's way with no other point of
  // the polygon inside.
  std::size_t i = 0, misses = 0;
  while (left.size() > 3 && misses < left.size()) {
    const std::size_t m = left.size();
    const std::size_t a = left[(i + m - 1) % m], b = left[i % m], c = left[(i + 1) % m];
    bool ear = cross2(p[b] - p[a], p[c] - p[b]) > 0.0;
    for (std::size_t k = 0; ear && k < m; ++k) {
      const std::size_t q = left[k];
      if (q != a && q != b && q != c && inside(p[q], p[a], p[b], p[c])) ear = false;
    }
    if (ear) {
      out.push_back({ids[a], ids[b], ids[c]});
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(i % m));
      i %= left.size();
      misses = 0;
    } else {
      i = (i + 1) % m;
      ++misses;
    }
  }
  // The last triangle, or what is left of a polygon that is not simple.
  std::vector<std::size_t> rest(left.begin() + static_cast<std::ptrdiff_t>(i % left.size()),
                                left.end());
  rest.insert(rest.end(), left.begin(),
              left.begin() + static_cast<std::ptrdiff_t>(i % left.size()));
  fan(rest);
  return out;
}

}  // namespace ibfvs
