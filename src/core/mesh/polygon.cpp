#include "ibfvs/core/mesh/polygon.h"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "ibfvs/core/support/error.h"

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
  // Every corner turns the polygon's way (counter-clockwise about the
  // normal) by more than kStraight of its two edges: a fan then has no
  // triangle with its three points on a line. A straight corner (a point
  // on an edge: a neighbour's refinement) goes to ear clipping, which
  // never takes it as an ear's tip.
  const auto turns = [&](std::size_t a, std::size_t b, std::size_t c) {
    const glm::dvec2 e1 = p[b] - p[a], e2 = p[c] - p[b];
    return cross2(e1, e2) > kStraight * glm::length(e1) * glm::length(e2);
  };
  bool convex = true;
  for (std::size_t k = 0; k < n && convex; ++k) convex = turns(k, (k + 1) % n, (k + 2) % n);
  if (convex || n > kMostClipped) {
    fan(left);
    return out;
  }
  // Ear clipping in the polygon's order: the ear at left[i] is its corner
  // with the neighbours, turning the polygon's way by more than kStraight
  // (a straight corner is never a tip) with no other point of the polygon
  // inside.
  std::size_t i = 0, misses = 0;
  while (left.size() > 3 && misses < left.size()) {
    const std::size_t m = left.size();
    const std::size_t a = left[(i + m - 1) % m], b = left[i % m], c = left[(i + 1) % m];
    bool ear = turns(a, b, c);
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

std::array<Triangle, 2> split_quad(std::span<const std::uint32_t, 4> q,
                                   std::span<const glm::vec3> points) {
  const auto distance2 = [&](int i, int j) {
    const glm::dvec3 d = glm::dvec3(points[q[static_cast<std::size_t>(i)]]) -
                         glm::dvec3(points[q[static_cast<std::size_t>(j)]]);
    return d.x * d.x + d.y * d.y + d.z * d.z;
  };
  if (distance2(0, 2) < distance2(1, 3) * (1.0 - 2e-3))
    return {{{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}};
  return {{{q[0], q[1], q[3]}, {q[1], q[2], q[3]}}};
}

template <std::signed_integral Index>
PolygonSplit split_polygons(const PolygonList<Index>& polygons, std::span<const glm::vec3> points) {
  PolygonSplit out;
  const std::size_t count = polygons.size();
  if (count == 0) return out;
  if (polygons.offsets[0] != 0 || static_cast<std::uint64_t>(polygons.offsets[count]) !=
                                      static_cast<std::uint64_t>(polygons.ids.size()))
    throw InputError("polygons: the offsets do not span the point ids");
  out.triangles.reserve(2 * count);
  out.polygon.reserve(2 * count);
  std::vector<std::uint32_t> ids;
  const auto take = [&](const Triangle& t, std::size_t c) {
    const bool within = t[0] < points.size() && t[1] < points.size() && t[2] < points.size();
    bool degenerate = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (within && !degenerate) {  // remove_degenerate_triangles's test, in the same floats
      const glm::vec3 n = glm::cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
      degenerate = !(glm::dot(n, n) > 0.0f);
    }
    if (degenerate) {
      ++out.dropped;
      return;
    }
    out.triangles.push_back(t);
    out.polygon.push_back(static_cast<std::uint32_t>(c));
  };
  for (std::size_t c = 0; c < count; ++c) {
    const Index begin = polygons.offsets[c], end = polygons.offsets[c + 1];
    if (end < begin)
      throw InputError("polygons: the offsets decrease at polygon " + std::to_string(c));
    const auto n = static_cast<std::size_t>(end - begin);
    if (n < 3) continue;
    ids.resize(n);
    bool within = true;
    for (std::size_t k = 0; k < n; ++k) {
      const Index id = polygons.ids[static_cast<std::size_t>(begin) + k];
      within = within && id >= 0 && static_cast<std::uint64_t>(id) < points.size();
      ids[k] = static_cast<std::uint32_t>(id);
    }
    if (n == 3) {
      take({ids[0], ids[1], ids[2]}, c);
    } else if (!within) {  // a point that is not there: validate_mesh names it
      for (std::size_t k = 1; k + 1 < n; ++k) {
        out.triangles.push_back({ids[0], ids[k], ids[k + 1]});
        out.polygon.push_back(static_cast<std::uint32_t>(c));
      }
    } else if (n == 4) {
      for (const Triangle& t : split_quad(std::span<const std::uint32_t, 4>(ids.data(), 4), points))
        take(t, c);
    } else {
      for (const Triangle& t : triangulate_polygon(ids, points)) take(t, c);
    }
  }
  return out;
}

template PolygonSplit split_polygons(const PolygonList<int>&, std::span<const glm::vec3>);
template PolygonSplit split_polygons(const PolygonList<long>&, std::span<const glm::vec3>);
template PolygonSplit split_polygons(const PolygonList<long long>&, std::span<const glm::vec3>);

}  // namespace ibfvs
