// Separation and attachment lines (topology.h): the zero contour of
// n . (w x Jw) over the vertices, classified by the Jacobian's eigenvalues
// and chained into polylines.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "ibfvs/core/fields/topology.h"

namespace ibfvs {
namespace {

// The field and its Jacobian at the vertices.
struct VertexField {
  std::vector<glm::dvec3> normal, w;  // w: tangent to the normal
  std::vector<glm::dmat3> jacobian;   // tangent: P J P
  double rate = 0.0;                  // area-weighted RMS of |J|
  double mean_edge = 0.0;
};

VertexField vertex_field(const TriMesh& mesh, std::span<const glm::vec3> vectors) {
  const std::size_t n = mesh.positions.size();
  VertexField f;
  f.normal.assign(n, glm::dvec3(0.0));
  f.w.assign(n, glm::dvec3(0.0));
  f.jacobian.assign(n, glm::dmat3(0.0));
  std::vector<double> weight(n, 0.0);
  double rate2 = 0.0, area_sum = 0.0, edge_sum = 0.0;
  for (const Triangle& t : mesh.triangles) {
    const glm::dvec3 p0(mesh.positions[t[0]]), p1(mesh.positions[t[1]]), p2(mesh.positions[t[2]]);
    const glm::dvec3 u = p1 - p0, v = p2 - p0;
    edge_sum += glm::length(u) + glm::length(v) + glm::length(p2 - p1);
    const glm::dvec3 cross = glm::cross(u, v);
    const double area2 = glm::length(cross);
    if (!(area2 > 1e-12 * glm::dot(u, u) + 1e-300)) continue;
    const glm::dvec3 nrm = cross / area2, e1 = glm::normalize(u), e2 = glm::cross(nrm, e1);
    // The triangle's linear field in its plane: J = M X^-1.
    double m[2][2], x[2][2];
    for (int c = 0; c < 2; ++c) {
      const glm::dvec3 d = glm::dvec3(vectors[t[c + 1]]) - glm::dvec3(vectors[t[0]]);
      const glm::dvec3 e = c == 0 ? u : v;
      m[0][c] = glm::dot(d, e1);
      m[1][c] = glm::dot(d, e2);
      x[0][c] = glm::dot(e, e1);
      x[1][c] = glm::dot(e, e2);
    }
    const double xdet = x[0][0] * x[1][1] - x[0][1] * x[1][0];
    const double xi[2][2] = {{x[1][1] / xdet, -x[0][1] / xdet}, {-x[1][0] / xdet, x[0][0] / xdet}};
    double j[2][2];
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) j[r][c] = m[r][0] * xi[0][c] + m[r][1] * xi[1][c];
    // In 3D: J3 = E J E^T with E = [e1 e2] (glm: column-major, J3[col][row]).
    glm::dmat3 j3(0.0);
    const glm::dvec3 axes[2] = {e1, e2};
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) j3 += j[r][c] * glm::outerProduct(axes[r], axes[c]);
    const double area = 0.5 * area2;
    rate2 += area * (j[0][0] * j[0][0] + j[0][1] * j[0][1] + j[1][0] * j[1][0] + j[1][1] * j[1][1]);
    area_sum += area;
    for (const std::uint32_t k : t) {
      f.jacobian[k] += area * j3;
      f.normal[k] += area * nrm;
      weight[k] += area;
    }
  }
  f.rate = area_sum > 0.0 ? std::sqrt(rate2 / area_sum) : 0.0;
  f.mean_edge = mesh.triangles.empty() ? 0.0 : edge_sum / (3.0 * mesh.triangles.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double len = glm::length(f.normal[i]);
    if (!(weight[i] > 0.0) || !(len > 0.0)) continue;
    const glm::dvec3 nrm = f.normal[i] / len;
    f.normal[i] = nrm;
    const glm::dmat3 p = glm::dmat3(1.0) - glm::outerProduct(nrm, nrm);
    f.jacobian[i] = p * (f.jacobian[i] / weight[i]) * p;
    const glm::dvec3 v(vectors[i]);
    f.w[i] = v - glm::dot(v, nrm) * nrm;
  }
  return f;
}

// The real eigenvalues (ascending) and eigenvectors of J restricted to the
// plane with normal n; none where they are complex.
struct Eigen {
  double value[2];
  glm::dvec3 vector[2];
};

std::optional<Eigen> tangent_eigen(const glm::dmat3& j3, const glm::dvec3& n) {
  glm::dvec3 e1 = glm::cross(n, glm::dvec3(1, 0, 0));
  if (glm::dot(e1, e1) < 0.1) e1 = glm::cross(n, glm::dvec3(0, 1, 0));
  e1 = glm::normalize(e1);
  const glm::dvec3 e2 = glm::cross(n, e1);
  const double a = glm::dot(e1, j3 * e1), b = glm::dot(e1, j3 * e2), c = glm::dot(e2, j3 * e1),
               d = glm::dot(e2, j3 * e2);
  const double trace = a + d, det = a * d - b * c, disc = trace * trace - 4.0 * det;
  if (disc < 0.0) return std::nullopt;
  const double root = std::sqrt(disc);
  Eigen e{{0.5 * (trace - root), 0.5 * (trace + root)}, {}};
  for (int k = 0; k < 2; ++k) {
    // (J - l I) x = 0: x = (b, l - a) or (l - d, c), whichever is longer.
    const double l = e.value[k];
    const double x1 = b, y1 = l - a, x2 = l - d, y2 = c;
    const bool first = x1 * x1 + y1 * y1 >= x2 * x2 + y2 * y2;
    const double x = first ? x1 : x2, y = first ? y1 : y2;
    const glm::dvec3 vec = x * e1 + y * e2;
    const double len = glm::length(vec);
    e.vector[k] = len > 0.0 ? vec / len : (k == 0 ? e1 : e2);
  }
  return e;
}

struct Classified {
  LineKind kind;
  double strength;
};

// Kenwright, Henze and Levit's test where w is parallel to an eigenvector:
// the other eigenvalue says whether the flow converges onto the line.
std::optional<Classified> classify(const glm::dvec3& w, const glm::dmat3& j3, const glm::dvec3& n) {
  const double speed = glm::length(w);
  if (!(speed > 0.0)) return std::nullopt;
  const std::optional<Eigen> e = tangent_eigen(j3, n);
  if (!e) return std::nullopt;
  const glm::dvec3 dir = w / speed;
  const double s0 = glm::length(glm::cross(dir, e->vector[0]));
  const double s1 = glm::length(glm::cross(dir, e->vector[1]));
  const int along = s0 <= s1 ? 0 : 1;
  if (std::min(s0, s1) > 0.5) return std::nullopt;  // not parallel: off the locus
  const double la = e->value[along], lb = e->value[1 - along];
  if (lb < 0.0 && lb < la) return Classified{LineKind::Separation, -lb};
  if (lb > 0.0 && lb > la) return Classified{LineKind::Attachment, lb};
  return std::nullopt;
}

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b);
}

struct Segment {
  std::uint64_t end[2];
  LineKind kind;
  double strength;
};

}  // namespace

const char* kind_name(LineKind kind) {
  return kind == LineKind::Separation ? "separation line" : "attachment line";
}

FeatureLines find_feature_lines(const TriMesh& mesh, std::span<const glm::vec3> vectors,
                                const LineOptions& options) {
  check_topology_input(mesh, vectors);
  const VertexField f = vertex_field(mesh, vectors);
  FeatureLines out;
  out.rate = f.rate;
  out.mean_edge = f.mean_edge;
  if (!(f.rate > 0.0)) return out;  // a zero or uniform field: no lines
  const std::size_t n = mesh.positions.size();
  std::vector<double> s(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    s[i] = glm::dot(f.normal[i], glm::cross(f.w[i], f.jacobian[i] * f.w[i]));
  // The contour's points on edges, by edge.
  std::unordered_map<std::uint64_t, LinePoint> crossing;
  const auto cross_edge = [&](std::uint32_t a, std::uint32_t b) {
    const std::uint64_t key = edge_key(a, b);
    if (crossing.count(key)) return key;
    const double t = s[a] / (s[a] - s[b]);
    LinePoint p;
    const glm::dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]);
    p.position = glm::vec3(pa + t * (pb - pa));
    p.magnitude = static_cast<float>(glm::length((1.0 - t) * f.w[a] + t * f.w[b]));
    glm::dvec3 nrm = (1.0 - t) * f.normal[a] + t * f.normal[b];
    if (glm::length(nrm) > 0.0) nrm = glm::normalize(nrm);
    p.normal = glm::vec3(nrm);
    if (const auto e = tangent_eigen((1.0 - t) * f.jacobian[a] + t * f.jacobian[b], nrm))
      p.eigen = {e->value[0], e->value[1]};
    crossing.emplace(key, p);
    return key;
  };
  const double floor_strength = options.min_strength * f.rate;
  std::vector<Segment> segments;
  for (const Triangle& t : mesh.triangles) {
    const bool pos[3] = {s[t[0]] >= 0.0, s[t[1]] >= 0.0, s[t[2]] >= 0.0};
    if (pos[0] == pos[1] && pos[1] == pos[2]) continue;
    // The corner on its own side, and the two edges from it.
    const int lone = pos[0] != pos[1] && pos[0] != pos[2] ? 0 : (pos[1] != pos[0] ? 1 : 2);
    const std::uint32_t a = t[lone], b = t[(lone + 1) % 3], c = t[(lone + 2) % 3];
    const glm::dvec3 p0(mesh.positions[t[0]]), p1(mesh.positions[t[1]]), p2(mesh.positions[t[2]]);
    const glm::dvec3 cross = glm::cross(p1 - p0, p2 - p0);
    if (!(glm::length(cross) > 0.0)) continue;
    // Classified at the segment's middle: the mean of its two ends' weights.
    const double tb = s[a] / (s[a] - s[b]), tc = s[a] / (s[a] - s[c]);
    const double wb = 0.5 * tb, wc = 0.5 * tc, wa = 1.0 - wb - wc;
    const glm::dvec3 nrm = glm::normalize(cross);
    const glm::dvec3 w = wa * f.w[a] + wb * f.w[b] + wc * f.w[c];
    const glm::dmat3 j = wa * f.jacobian[a] + wb * f.jacobian[b] + wc * f.jacobian[c];
    const std::optional<Classified> k = classify(w - glm::dot(w, nrm) * nrm, j, nrm);
    if (!k || k->strength < floor_strength) continue;
    segments.push_back({{cross_edge(a, b), cross_edge(a, c)}, k->kind, k->strength});
  }
  // Chains of segments of one kind through the edges they share.
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> at;  // (edge, kind) -> segments
  const auto node = [](std::uint64_t edge, LineKind kind) {
    return edge * 2 + (kind == LineKind::Attachment ? 1 : 0);
  };
  for (std::size_t i = 0; i < segments.size(); ++i)
    for (const std::uint64_t e : segments[i].end) at[node(e, segments[i].kind)].push_back(i);
  std::vector<char> used(segments.size(), 0);
  const auto next = [&](std::size_t from, std::uint64_t edge) -> std::optional<std::size_t> {
    for (const std::size_t k : at[node(edge, segments[from].kind)])
      if (k != from && !used[k]) return k;
    return std::nullopt;
  };
  const double min_length = options.min_length * f.mean_edge;
  for (std::size_t start = 0; start < segments.size(); ++start) {
    if (used[start]) continue;
    used[start] = 1;
    // Walk both ways from the segment: back from end[0], on from end[1].
    std::vector<std::uint64_t> back{segments[start].end[0]}, on{segments[start].end[1]};
    std::vector<std::size_t> members{start};
    bool closed = false;
    for (int dir = 0; dir < 2 && !closed; ++dir) {
      std::vector<std::uint64_t>& path = dir == 0 ? on : back;
      std::size_t at_segment = start;
      while (const auto k = next(at_segment, path.back())) {
        used[*k] = 1;
        members.push_back(*k);
        const Segment& g = segments[*k];
        const std::uint64_t far = g.end[0] == path.back() ? g.end[1] : g.end[0];
        if (far == (dir == 0 ? back.front() : on.front())) {
          closed = true;
          break;
        }
        path.push_back(far);
        at_segment = *k;
      }
    }
    FeatureLine line;
    line.kind = segments[start].kind;
    line.closed = closed;
    for (auto it = back.rbegin(); it != back.rend(); ++it) line.points.push_back(crossing[*it]);
    for (const std::uint64_t e : on) line.points.push_back(crossing[e]);
    for (std::size_t i = 1; i < line.points.size(); ++i)
      line.length += glm::length(line.points[i].position - line.points[i - 1].position);
    if (closed)
      line.length += glm::length(line.points.front().position - line.points.back().position);
    double sum = 0.0;
    for (const std::size_t m : members) sum += segments[m].strength;
    line.strength = sum / static_cast<double>(members.size());
    if (line.length >= min_length) out.lines.push_back(std::move(line));
  }
  return out;
}

std::size_t FlowTopology::count(CriticalKind kind) const {
  return static_cast<std::size_t>(
      std::count_if(critical.points.begin(), critical.points.end(),
                    [&](const CriticalPoint& p) { return p.kind == kind; }));
}

std::size_t FlowTopology::count(LineKind kind) const {
  return static_cast<std::size_t>(
      std::count_if(lines.lines.begin(), lines.lines.end(),
                    [&](const FeatureLine& l) { return l.kind == kind; }));
}

FlowTopology find_topology(const TriMesh& mesh, std::span<const glm::vec3> vectors,
                           const LineOptions& options) {
  FlowTopology t;
  t.critical = find_critical_points(mesh, vectors);
  t.lines = find_feature_lines(mesh, vectors, options);
  return t;
}

}  // namespace ibfvs
