#include "ibfvs/core/fields/surface_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "ibfvs/core/fields/topology.h"

namespace ibfvs {
namespace {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b);
}

}  // namespace

SurfaceField::SurfaceField(const TriMesh& mesh, std::span<const glm::vec3> vectors) : mesh_(mesh) {
  check_topology_input(mesh, vectors);
  const std::size_t n = mesh.positions.size(), nt = mesh.triangles.size();
  normal_.assign(n, glm::dvec3(0.0));
  frames_.resize(nt);
  std::vector<double> ring_area(n, 0.0);
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  double edge_sum = 0.0;
  for (std::size_t f = 0; f < nt; ++f) {
    const Triangle& t = mesh.triangles[f];
    const glm::dvec3 p0(mesh.positions[t[0]]), p1(mesh.positions[t[1]]), p2(mesh.positions[t[2]]);
    frames_[f] = triangle_frame(p0, p1, p2);
    edge_sum += glm::length(p1 - p0) + glm::length(p2 - p1) + glm::length(p0 - p2);
    for (const glm::dvec3& p : {p0, p1, p2}) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    if (!frames_[f].valid) continue;
    for (const std::uint32_t k : t) {
      normal_[k] += frames_[f].area * frames_[f].normal;
      ring_area[k] += frames_[f].area;
    }
  }
  mean_edge_ = nt ? edge_sum / (3.0 * static_cast<double>(nt)) : 0.0;
  size_ = nt ? glm::length(hi - lo) : 0.0;
  tangent_.resize(n);
  direction_.assign(n, glm::dvec3(0.0));
  for (std::size_t i = 0; i < n; ++i) {
    const double len = glm::length(normal_[i]);
    const glm::dvec3 v(vectors[i]);
    if (len > 0.0) {
      normal_[i] /= len;
      tangent_[i] = v - glm::dot(v, normal_[i]) * normal_[i];
    } else {
      normal_[i] = glm::dvec3(0, 0, 1);
      tangent_[i] = v;
    }
    const double speed = glm::length(tangent_[i]);
    if (speed > 0.0 && std::isfinite(speed)) direction_[i] = tangent_[i] / speed;
  }
  // Neighbours across each edge (an edge of more than two triangles is a
  // boundary for the traces: which side to go on is not defined).
  std::unordered_map<std::uint64_t, std::array<std::uint32_t, 3>> edges;  // tri, edge, count
  edges.reserve(nt * 2);
  for (std::uint32_t f = 0; f < nt; ++f)
    for (int k = 0; k < 3; ++k) {
      const Triangle& t = mesh.triangles[f];
      auto [it, fresh] = edges.try_emplace(edge_key(t[k], t[(k + 1) % 3]),
                                           std::array<std::uint32_t, 3>{f, std::uint32_t(k), 0});
      ++it->second[2];
      (void)fresh;
    }
  across_.assign(nt, {kNoTriangle, kNoTriangle, kNoTriangle});
  across_edge_.assign(nt, {-1, -1, -1});
  for (std::uint32_t f = 0; f < nt; ++f)
    for (int k = 0; k < 3; ++k) {
      const Triangle& t = mesh.triangles[f];
      const auto& e = edges.at(edge_key(t[k], t[(k + 1) % 3]));
      if (e[2] != 2 || e[0] == f) continue;
      across_[f][k] = e[0];
      across_edge_[f][k] = static_cast<std::int8_t>(e[1]);
      across_[e[0]][e[1]] = f;
      across_edge_[e[0]][e[1]] = static_cast<std::int8_t>(k);
    }
  // Vertex fans.
  fan_start_.assign(n + 1, 0);
  for (const Triangle& t : mesh.triangles)
    for (const std::uint32_t k : t) ++fan_start_[k + 1];
  for (std::size_t i = 0; i < n; ++i) fan_start_[i + 1] += fan_start_[i];
  fan_.resize(fan_start_[n]);
  std::vector<std::uint32_t> fill(fan_start_.begin(), fan_start_.end() - 1);
  for (std::uint32_t f = 0; f < nt; ++f)
    for (const std::uint32_t k : mesh.triangles[f]) fan_[fill[k]++] = f;
  // Per triangle: the Jacobian, the directions in its plane, their divergence.
  jacobian_.resize(nt);
  divergence_.assign(nt, 0.0);
  corner_dir_.resize(nt);
  smooth_speed_.assign(n, 0.0);
  std::vector<double> speed_weight(n, 0.0);
  for (std::uint32_t f = 0; f < nt; ++f) {
    const TriangleFrame& fr = frames_[f];
    if (!fr.valid) continue;
    const Triangle& t = mesh.triangles[f];
    const glm::dvec3 p1(mesh.positions[t[1]]), p2(mesh.positions[t[2]]);
    jacobian_[f] = triangle_jacobian(fr, p1, p2, tangent_[t[0]], tangent_[t[1]], tangent_[t[2]]);
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3& d = direction_[t[k]];
      corner_dir_[f][k] = d - glm::dot(d, fr.normal) * fr.normal;
    }
    const Mat2 jd =
        triangle_jacobian(fr, p1, p2, corner_dir_[f][0], corner_dir_[f][1], corner_dir_[f][2]);
    // div(D / |D|) at the centroid, D the linear directions.
    const glm::dvec3 dc = (corner_dir_[f][0] + corner_dir_[f][1] + corner_dir_[f][2]) / 3.0;
    const auto c = fr.of(dc);
    const double len = std::hypot(c[0], c[1]);
    if (len > 1e-6) {
      const double jx = jd.a * c[0] + jd.b * c[1], jy = jd.c * c[0] + jd.d * c[1];
      divergence_[f] = jd.trace() / len - (c[0] * jx + c[1] * jy) / (len * len * len);
    }
    const double mean_speed =
        (glm::length(tangent_[t[0]]) + glm::length(tangent_[t[1]]) + glm::length(tangent_[t[2]])) /
        3.0;
    for (const std::uint32_t k : t) {
      smooth_speed_[k] += fr.area * mean_speed;
      speed_weight[k] += fr.area;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    smooth_speed_[i] = speed_weight[i] > 0.0 ? smooth_speed_[i] / speed_weight[i] : 0.0;
}

std::array<double, 3> SurfaceField::barycentric(std::uint32_t t, const glm::dvec3& p) const {
  const TriangleFrame& fr = frames_[t];
  const Triangle& tri = mesh_.triangles[t];
  const auto x1 = fr.of(glm::dvec3(mesh_.positions[tri[1]]) - fr.origin);
  const auto x2 = fr.of(glm::dvec3(mesh_.positions[tri[2]]) - fr.origin);
  const auto q = fr.of(p - fr.origin);
  const double det = x1[0] * x2[1] - x2[0] * x1[1];
  if (det == 0.0) return {1.0, 0.0, 0.0};
  const double b1 = (q[0] * x2[1] - x2[0] * q[1]) / det;
  const double b2 = (x1[0] * q[1] - q[0] * x1[1]) / det;
  return {1.0 - b1 - b2, b1, b2};
}

glm::dvec3 SurfaceField::field_at(const SurfacePoint& p) const {
  const auto b = barycentric(p.triangle, p.position);
  const Triangle& t = mesh_.triangles[p.triangle];
  const glm::dvec3 w = b[0] * tangent_[t[0]] + b[1] * tangent_[t[1]] + b[2] * tangent_[t[2]];
  const glm::dvec3& n = frames_[p.triangle].normal;
  return w - glm::dot(w, n) * n;
}

glm::dvec3 SurfaceField::direction_at(const SurfacePoint& p) const {
  const auto b = barycentric(p.triangle, p.position);
  const auto& d = corner_dir_[p.triangle];
  return b[0] * d[0] + b[1] * d[1] + b[2] * d[2];
}

double SurfaceField::smooth_speed_at(const SurfacePoint& p) const {
  const auto b = barycentric(p.triangle, p.position);
  const Triangle& t = mesh_.triangles[p.triangle];
  return b[0] * smooth_speed_[t[0]] + b[1] * smooth_speed_[t[1]] + b[2] * smooth_speed_[t[2]];
}

glm::dvec3 SurfaceField::normal_at(const SurfacePoint& p) const {
  const auto b = barycentric(p.triangle, p.position);
  const Triangle& t = mesh_.triangles[p.triangle];
  const glm::dvec3 n = b[0] * normal_[t[0]] + b[1] * normal_[t[1]] + b[2] * normal_[t[2]];
  const double len = glm::length(n);
  return len > 0.0 ? n / len : frames_[p.triangle].normal;
}

namespace {

// The unit direction at x in triangle t (x in its plane; outside it, the
// linear directions extrapolated), or zero where they vanish.
glm::dvec3 unit_direction(const SurfaceField& f, std::uint32_t t, const glm::dvec3& x, int sense) {
  const glm::dvec3 d = f.direction_at({t, x});
  const double len = glm::length(d);
  return len > 1e-9 ? static_cast<double>(sense) * d / len : glm::dvec3(0.0);
}

}  // namespace

Trace trace_line(const SurfaceField& field, const SurfacePoint& start, int sense, double max_length,
                 double step, const TraceVisitor& visit) {
  Trace out;
  const TriMesh& mesh = field.mesh();
  if (start.triangle >= field.triangle_count() || !field.frame(start.triangle).valid) {
    out.end = TraceEnd::Stalled;
    return out;
  }
  std::uint32_t t = start.triangle;
  glm::dvec3 x = start.position;
  {  // onto the triangle's plane
    const TriangleFrame& fr = field.frame(t);
    x -= glm::dot(x - fr.origin, fr.normal) * fr.normal;
  }
  double arc = 0.0;
  out.points.push_back({x, t, 0.0});
  if (visit && !visit(out)) {
    out.end = TraceEnd::Stopped;
    return out;
  }
  int idle = 0;  // moves across edges without progress (walking round a vertex)
  while (arc < max_length) {
    const TriangleFrame& fr = field.frame(t);
    const double h = std::min({step, 0.25 * std::sqrt(2.0 * fr.area), max_length - arc});
    const glm::dvec3 k1 = unit_direction(field, t, x, sense);
    if (k1 == glm::dvec3(0.0)) {
      out.end = TraceEnd::Stalled;
      return out;
    }
    const glm::dvec3 k2 = unit_direction(field, t, x + 0.5 * h * k1, sense);
    const glm::dvec3 k3 = unit_direction(field, t, x + 0.5 * h * k2, sense);
    const glm::dvec3 k4 = unit_direction(field, t, x + h * k3, sense);
    glm::dvec3 dx = (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
    if (glm::length(dx) < 1e-9) {
      out.end = TraceEnd::Stalled;
      return out;
    }
    dx *= h / glm::length(dx);  // a step of arc length h
    const auto b0 = field.barycentric(t, x);
    const auto b1 = field.barycentric(t, x + dx);
    double leave = 2.0;
    int edge = -1;  // the corner opposite the edge it leaves by
    for (int i = 0; i < 3; ++i)
      if (b1[i] < 0.0) {
        const double tau = std::max(b0[i], 0.0) / (std::max(b0[i], 0.0) - b1[i]);
        if (tau < leave) {
          leave = tau;
          edge = i;
        }
      }
    if (edge < 0) {
      x += dx;
      arc += h;
      idle = 0;
      out.points.push_back({x, t, arc});
      if (visit && !visit(out)) {
        out.end = TraceEnd::Stopped;
        return out;
      }
      continue;
    }
    // To the edge, and across it: the edge opposite corner `edge` runs
    // from corner edge+1 to edge+2, which is the triangle's edge k = edge+1.
    x += leave * dx;
    arc += leave * h;
    const int k = (edge + 1) % 3;
    const std::uint32_t next = field.neighbour(t, k);
    if (leave > 1e-9) {
      idle = 0;
      out.points.push_back({x, t, arc});
      if (visit && !visit(out)) {
        out.end = TraceEnd::Stopped;
        return out;
      }
    } else if (++idle > 64) {
      out.end = TraceEnd::Stalled;
      return out;
    }
    if (next == kNoTriangle || !field.frame(next).valid) {
      out.end = TraceEnd::Boundary;
      return out;
    }
    // The point is on the shared edge: its position in the next triangle's
    // plane from the two shared corners' weights.
    const Triangle& tri = mesh.triangles[t];
    const std::uint32_t va = tri[k], vb = tri[(k + 1) % 3];
    const auto bb = field.barycentric(t, x);
    double wa = std::max(bb[k], 0.0), wb = std::max(bb[(k + 1) % 3], 0.0);
    const double sum = wa + wb;
    wa = sum > 0.0 ? wa / sum : 0.5;
    wb = 1.0 - wa;
    const glm::dvec3 on_edge =
        wa * glm::dvec3(mesh.positions[va]) + wb * glm::dvec3(mesh.positions[vb]);
    // Does the flow in the next triangle carry the point into it? Where it
    // points back across the edge, both sides flow into the edge: the line
    // has met a line onto which the flow converges (a line of zeros).
    const TriangleFrame& nf = field.frame(next);
    const glm::dvec3 dn = unit_direction(field, next, on_edge, sense);
    const glm::dvec3 opposite_n =
        glm::dvec3(mesh.positions[mesh.triangles[next][(field.neighbour_edge(t, k) + 2) % 3]]);
    glm::dvec3 inward = opposite_n - on_edge;
    const glm::dvec3 along =
        glm::normalize(glm::dvec3(mesh.positions[vb]) - glm::dvec3(mesh.positions[va]));
    inward -= glm::dot(inward, along) * along;
    inward -= glm::dot(inward, nf.normal) * nf.normal;
    if (dn == glm::dvec3(0.0)) {
      out.end = TraceEnd::Stalled;
      return out;
    }
    if (glm::dot(dn, inward) < -1e-6 * glm::length(inward)) {
      out.end = TraceEnd::Converged;
      return out;
    }
    t = next;
    x = on_edge;
  }
  out.end = TraceEnd::Length;
  return out;
}

}  // namespace ibfvs
