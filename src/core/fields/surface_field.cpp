#include "ibfvs/core/fields/surface_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "ibfvs/core/fields/topology.h"

namespace ibfvs {
namespace {}  // namespace

SurfaceField::SurfaceField(const TriMesh& mesh, std::span<const glm::vec3> vectors) : mesh_(mesh) {
  check_topology_input(mesh, vectors);
  const std::size_t n = mesh.positions.size(), nt = mesh.triangles.size();
  normal_.assign(n, glm::dvec3(0.0));
  frames_.resize(nt);
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
    }
  }
  mean_edge_ = nt ? edge_sum / (3.0 * static_cast<double>(nt)) : 0.0;
  size_ = nt ? glm::length(hi - lo) : 0.0;
  if (nt) lo_ = lo, hi_ = hi;
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
  // Vertex fans.
  fan_start_.assign(n + 1, 0);
  for (const Triangle& t : mesh.triangles)
    for (const std::uint32_t k : t) ++fan_start_[k + 1];
  for (std::size_t i = 0; i < n; ++i) fan_start_[i + 1] += fan_start_[i];
  fan_.resize(fan_start_[n]);
  std::vector<std::uint32_t> fill(fan_start_.begin(), fan_start_.end() - 1);
  for (std::uint32_t f = 0; f < nt; ++f)
    for (const std::uint32_t k : mesh.triangles[f]) fan_[fill[k]++] = f;
  // Neighbours across each edge, from the fan of its first corner: the one
  // other triangle with both its corners (none where there are more: which
  // side a trace goes on at a non-manifold edge is not defined).
  across_.assign(nt, {kNoTriangle, kNoTriangle, kNoTriangle});
  across_edge_.assign(nt, {-1, -1, -1});
#pragma omp parallel for schedule(static)
  for (std::int64_t fi = 0; fi < static_cast<std::int64_t>(nt); ++fi) {
    const auto f = static_cast<std::uint32_t>(fi);
    const Triangle& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      std::uint32_t other = kNoTriangle;
      int other_edge = -1, count = 0;
      for (const std::uint32_t g : fan(a)) {
        if (g == f) continue;
        const Triangle& u = mesh.triangles[g];
        for (int e = 0; e < 3; ++e)
          if ((u[e] == b && u[(e + 1) % 3] == a) || (u[e] == a && u[(e + 1) % 3] == b)) {
            other = g;
            other_edge = e;
            ++count;
          }
      }
      if (count == 1) {
        across_[f][k] = other;
        across_edge_[f][k] = static_cast<std::int8_t>(other_edge);
      }
    }
  }
  corners_.assign(nt, Corners{0, 0, 0, 0, 0});
  for (std::uint32_t f = 0; f < nt; ++f) {
    const TriangleFrame& fr = frames_[f];
    const Triangle& t = mesh.triangles[f];
    const auto x1 = fr.of(glm::dvec3(mesh.positions[t[1]]) - fr.origin);
    const auto x2 = fr.of(glm::dvec3(mesh.positions[t[2]]) - fr.origin);
    const double det = x1[0] * x2[1] - x2[0] * x1[1];
    corners_[f] = {x1[0], x1[1], x2[0], x2[1], det != 0.0 ? 1.0 / det : 0.0};
  }
  // Per triangle: the Jacobian, the directions in its plane, their divergence.
  jacobian_.resize(nt);
  divergence_.assign(nt, 0.0);
  corner_dir_.resize(nt);
#pragma omp parallel for schedule(static)
  for (std::int64_t fi = 0; fi < static_cast<std::int64_t>(nt); ++fi) {
    const auto f = static_cast<std::uint32_t>(fi);
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
  }
}

std::array<double, 3> SurfaceField::barycentric(std::uint32_t t, const glm::dvec3& p) const {
  const TriangleFrame& fr = frames_[t];
  const Corners& c = corners_[t];
  if (c.inv_det == 0.0) return {1.0, 0.0, 0.0};
  const glm::dvec3 d = p - fr.origin;
  const double qx = glm::dot(d, fr.e1), qy = glm::dot(d, fr.e2);
  const double b1 = (qx * c.y2 - c.x2 * qy) * c.inv_det;
  const double b2 = (c.x1 * qy - qx * c.y1) * c.inv_det;
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
    const double h = std::min({step, 0.5 * std::sqrt(2.0 * fr.area), max_length - arc});
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
