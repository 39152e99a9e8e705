#include "support/curvature_surfaces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include <glm/glm.hpp>

#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/mesh/subdivision.h"

#ifdef IBFVS_TEST_HAVE_CGAL
#ifndef CGAL_EIGEN3_ENABLED
#define CGAL_EIGEN3_ENABLED 1  // the jet fitting's solver
#endif
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>
#endif

namespace ibfvs::test {
namespace {

constexpr double kPi = std::numbers::pi;

// Principal curvatures and directions of a symmetric 3x3 operator H (the
// Hessian of an implicit function divided by its gradient's length)
// restricted to the plane normal to n, signed as Curvature.
void from_operator(const glm::dmat3& h, const glm::dvec3& n, float& kmin, float& kmax,
                   glm::vec3& dmin, glm::vec3& dmax) {
  const glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(a, n)), v = glm::cross(n, u);
  const double s11 = glm::dot(u, h * u), s12 = glm::dot(u, h * v), s22 = glm::dot(v, h * v);
  const double mean = 0.5 * (s11 + s22), radius = std::hypot(0.5 * (s11 - s22), s12);
  const double theta = 0.5 * std::atan2(2.0 * s12, s11 - s22);
  kmax = static_cast<float>(mean + radius);
  kmin = static_cast<float>(mean - radius);
  dmax = glm::vec3(std::cos(theta) * u + std::sin(theta) * v);
  dmin = glm::vec3(-std::sin(theta) * u + std::cos(theta) * v);
}

void finish(TestSurface& s) {
  compute_vertex_normals(s.mesh);
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < s.known.size(); ++i)
    if (s.known[i]) {
      sum += 0.5 * (double(s.kmin[i]) * s.kmin[i] + double(s.kmax[i]) * s.kmax[i]);
      ++count;
    }
  s.kappa_rms = count ? static_cast<float>(std::sqrt(sum / count)) : 0.0f;
}

void allocate(TestSurface& s) {
  const std::size_t n = s.mesh.vertex_count();
  s.kmin.assign(n, 0.0f);
  s.kmax.assign(n, 0.0f);
  s.dmin.assign(n, glm::vec3(0));
  s.dmax.assign(n, glm::vec3(0));
  s.known.assign(n, 0);
}

// A point uniformly distributed in the unit disc.
glm::dvec2 in_disc(std::mt19937& rng) {
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (;;) {
    const double y = uni(rng), x = uni(rng);  // one by one: the same with any compiler
    const glm::dvec2 d(x, y);
    if (glm::dot(d, d) <= 1.0) return d;
  }
}

// The ordered 1-ring of every vertex of a closed manifold triangle mesh
// (counter-clockwise as its triangles); empty where it is not a single fan.
std::vector<std::vector<std::uint32_t>> ordered_rings(const TriMesh& m) {
  const std::size_t n = m.vertex_count();
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> next(n);
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k) next[t[k]].emplace_back(t[(k + 1) % 3], t[(k + 2) % 3]);
  std::vector<std::vector<std::uint32_t>> rings(n);
  for (std::size_t v = 0; v < n; ++v) {
    const auto& e = next[v];
    if (e.empty()) continue;
    std::vector<std::uint32_t> ring{e[0].first};
    for (std::size_t step = 0; step < e.size(); ++step) {
      const auto it =
          std::find_if(e.begin(), e.end(), [&](const auto& p) { return p.first == ring.back(); });
      if (it == e.end()) break;
      if (it->second == ring.front()) {
        if (ring.size() == e.size()) rings[v] = ring;
        break;
      }
      ring.push_back(it->second);
    }
  }
  return rings;
}

}  // namespace

TestSurface jittered_torus(float R, float r, int segments, int sides, float jitter,
                           std::uint32_t seed) {
  TestSurface s;
  s.name = "torus R=" + std::to_string(R).substr(0, 4) + " r=" + std::to_string(r).substr(0, 4);
  s.mesh = make_torus(R, r, segments, sides);
  allocate(s);
  std::mt19937 rng(seed);
  for (int j = 0; j < sides; ++j)
    for (int i = 0; i < segments; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * segments + i;
      const glm::dvec2 d = jitter > 0.0f ? in_disc(rng) * double(jitter) : glm::dvec2(0);
      const double u = 2 * kPi * (i + d.x) / segments, v = 2 * kPi * (j + d.y) / sides;
      const glm::dvec3 dir(std::cos(u), 0, -std::sin(u));
      const glm::dvec3 n = std::cos(v) * dir + glm::dvec3(0, std::sin(v), 0);
      s.mesh.positions[k] = glm::vec3(double(R) * dir + double(r) * n);
      s.kmax[k] = 1.0f / r;
      s.kmin[k] = static_cast<float>(std::cos(v) / (R + r * std::cos(v)));
      s.dmax[k] = glm::vec3(-std::sin(v) * dir + glm::dvec3(0, std::cos(v), 0));
      s.dmin[k] = glm::vec3(-std::sin(u), 0, -std::cos(u));
      s.known[k] = 1;
    }
  finish(s);
  return s;
}

TestSurface jittered_ellipsoid(glm::vec3 radii, int level, float jitter, std::uint32_t seed) {
  TestSurface s;
  s.name = "ellipsoid";
  s.mesh = loop_subdivide(make_icosahedron(1.0f), level);
  allocate(s);
  // Mean edge length on the unit sphere, for the jitter.
  double edge = 0;
  for (const Triangle& t : s.mesh.triangles)
    edge += glm::length(glm::dvec3(s.mesh.positions[t[0]]) - glm::dvec3(s.mesh.positions[t[1]]));
  edge /= static_cast<double>(s.mesh.triangle_count());
  std::mt19937 rng(seed);
  const glm::dvec3 a(radii);
  for (std::size_t k = 0; k < s.mesh.vertex_count(); ++k) {
    const glm::dvec3 p = glm::normalize(glm::dvec3(s.mesh.positions[k]));
    const glm::dvec3 h = std::abs(p.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(h, p)), v = glm::cross(p, u);
    const glm::dvec2 d = in_disc(rng) * double(jitter) * edge;
    const glm::dvec3 x = glm::normalize(p + d.x * u + d.y * v) * a;
    s.mesh.positions[k] = glm::vec3(x);
    // F = sum x_i^2 / a_i^2 - 1: the shape operator is Hess F / |grad F|
    // on the tangent plane.
    const glm::dvec3 grad = 2.0 * x / (a * a);
    const double len = glm::length(grad);
    const glm::dmat3 hess(glm::dvec3(2.0 / (a.x * a.x), 0, 0), glm::dvec3(0, 2.0 / (a.y * a.y), 0),
                          glm::dvec3(0, 0, 2.0 / (a.z * a.z)));
    from_operator(hess / len, grad / len, s.kmin[k], s.kmax[k], s.dmin[k], s.dmax[k]);
    s.known[k] = 1;
  }
  finish(s);
  return s;
}

bool have_cgal() {
#ifdef IBFVS_TEST_HAVE_CGAL
  return true;
#else
  return false;
#endif
}

TestSurface random_sphere(float r, int points, std::uint32_t seed) {
  TestSurface s;
  s.name = "random sphere";
#ifdef IBFVS_TEST_HAVE_CGAL
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss;
  std::vector<K::Point_3> pts;
  for (int i = 0; i < points; ++i) {
    const double z = gauss(rng), y = gauss(rng), x = gauss(rng);  // one by one (any compiler)
    const glm::dvec3 d = glm::normalize(glm::dvec3(x, y, z)) * double(r);
    const glm::vec3 f(d);  // the mesh holds floats: hull exactly those
    pts.emplace_back(f.x, f.y, f.z);
  }
  CGAL::Surface_mesh<K::Point_3> hull;
  CGAL::convex_hull_3(pts.begin(), pts.end(), hull);
  // CGAL's order of vertices and faces changes from call to call (its
  // default random generator moves on): number the vertices by their input
  // point and sort the faces, so that the same seed gives the same mesh.
  std::map<std::array<double, 3>, std::uint32_t> input;
  for (std::size_t i = 0; i < pts.size(); ++i)
    input.emplace(std::array<double, 3>{pts[i].x(), pts[i].y(), pts[i].z()},
                  static_cast<std::uint32_t>(i));
  std::vector<std::uint32_t> index(pts.size(), 0), hull_input(hull.number_of_vertices());
  std::vector<std::uint8_t> used(pts.size(), 0);
  for (const auto v : hull.vertices()) {
    const auto& p = hull.point(v);
    hull_input[v.idx()] = input.at({p.x(), p.y(), p.z()});
    used[hull_input[v.idx()]] = 1;
  }
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (used[i]) {
      index[i] = static_cast<std::uint32_t>(s.mesh.positions.size());
      s.mesh.positions.emplace_back(pts[i].x(), pts[i].y(), pts[i].z());
    }
  for (const auto f : hull.faces()) {
    Triangle t{};
    int k = 0;
    for (const auto v : hull.vertices_around_face(hull.halfedge(f)))
      t[k++] = index[hull_input[v.idx()]];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // keeps orientation
    s.mesh.triangles.push_back(t);
  }
  std::sort(s.mesh.triangles.begin(), s.mesh.triangles.end());
  allocate(s);
  std::fill(s.kmin.begin(), s.kmin.end(), 1.0f / r);
  std::fill(s.kmax.begin(), s.kmax.end(), 1.0f / r);
  std::fill(s.known.begin(), s.known.end(), 1);  // umbilic everywhere: no directions
  finish(s);
#else
  (void)r, (void)points, (void)seed;
#endif
  return s;
}

TestSurface loop_limit_surface(const TriMesh& coarse, int levels, const std::string& name) {
  TestSurface s;
  s.name = name;
  TriMesh control = coarse;
  control.scalars.clear();
  control.vectors.clear();
  control.vector_arrays.clear();
  control = loop_subdivide(control, levels);
  const std::size_t n = control.vertex_count();
  const auto rings = ordered_rings(control);
  s.mesh = control;
  allocate(s);
  // Limit positions: Loop's mask (1 - n chi) p + chi sum q, chi = 1 / (n + 3 / (8 beta)),
  // beta = alpha(n) / n with OpenMesh's alpha(n) = (40 - (3 + 2 cos(2 pi / n))^2) / 64.
  for (std::size_t v = 0; v < n; ++v) {
    const auto& ring = rings[v];
    if (ring.size() < 3) continue;
    const double val = static_cast<double>(ring.size());
    const double t = 3.0 + 2.0 * std::cos(2.0 * kPi / val);
    const double beta = (40.0 - t * t) / 64.0 / val;
    const double chi = 1.0 / (val + 3.0 / (8.0 * beta));
    glm::dvec3 sum(0);
    for (const std::uint32_t q : ring) sum += glm::dvec3(control.positions[q]);
    s.mesh.positions[v] =
        glm::vec3((1.0 - val * chi) * glm::dvec3(control.positions[v]) + chi * sum);
  }
  // Regular vertices (their 3-ring all of valence 6): the six patches around
  // them are pieces of the quartic three-direction box spline, whose
  // derivatives at a vertex are sums over the 1-ring of control points. With
  // the ring q0..q5 at lattice steps e1, e1+e2, e2, -e1, -e1-e2, -e2:
  //   X_1 = (q0 - q3) / 3 + (q1 - q4) / 6 + (q5 - q2) / 6,
  //   X_2 = (q2 - q5) / 3 + (q1 - q4) / 6 + (q3 - q0) / 6,
  //   X_11 = q0 - 2p + q3, X_22 = q2 - 2p + q5, X_(1+2)(1+2) = q1 - 2p + q4,
  // the last from D_e^2 M_222 = second difference of M_022 along e, which is
  // the Kronecker delta on the lattice (as for cubic B-splines at knots).
  std::vector<std::uint8_t> regular(n, 0);
  for (std::size_t v = 0; v < n; ++v) regular[v] = rings[v].size() == 6;
  std::vector<std::uint8_t> ok = regular;
  for (int pass = 0; pass < 3; ++pass) {
    std::vector<std::uint8_t> next = ok;
    for (std::size_t v = 0; v < n; ++v)
      for (const std::uint32_t q : rings[v]) next[v] = next[v] && ok[q];
    ok = std::move(next);
  }
  std::vector<glm::vec3> vertex_normals = s.mesh.normals;
  {
    TriMesh tmp = s.mesh;
    compute_vertex_normals(tmp);
    vertex_normals = tmp.normals;
  }
  for (std::size_t v = 0; v < n; ++v) {
    if (!ok[v] || !regular[v]) continue;
    glm::dvec3 q[6];
    for (int k = 0; k < 6; ++k) q[k] = glm::dvec3(control.positions[rings[v][k]]);
    const glm::dvec3 p(control.positions[v]);
    const glm::dvec3 x1 = (q[0] - q[3]) / 3.0 + (q[1] - q[4]) / 6.0 + (q[5] - q[2]) / 6.0;
    const glm::dvec3 x2 = (q[2] - q[5]) / 3.0 + (q[1] - q[4]) / 6.0 + (q[3] - q[0]) / 6.0;
    const glm::dvec3 x11 = q[0] - 2.0 * p + q[3], x22 = q[2] - 2.0 * p + q[5];
    const glm::dvec3 x33 = q[1] - 2.0 * p + q[4];
    const glm::dvec3 x12 = 0.5 * (x33 - x11 - x22);
    glm::dvec3 nrm = glm::normalize(glm::cross(x1, x2));
    if (glm::dot(nrm, glm::dvec3(vertex_normals[v])) < 0.0) nrm = -nrm;
    // Shape operator -(I^-1 II) in the orthonormal basis (e1, e2), e1 along x1.
    const glm::dvec3 e1 = glm::normalize(x1), e2 = glm::cross(nrm, e1);
    const double a11 = glm::dot(x1, e1), a12 = glm::dot(x2, e1), a22 = glm::dot(x2, e2);
    const double l = glm::dot(x11, nrm), m = glm::dot(x12, nrm), nn = glm::dot(x22, nrm);
    const double i11 = 1.0 / a11, i12 = -a12 / (a11 * a22), i22 = 1.0 / a22;
    const double s11 = -(i11 * i11 * l);
    const double s12 = -(i11 * (i12 * l + i22 * m));
    const double s22 = -(i12 * i12 * l + 2.0 * i12 * i22 * m + i22 * i22 * nn);
    const double mean = 0.5 * (s11 + s22), radius = std::hypot(0.5 * (s11 - s22), s12);
    const double theta = 0.5 * std::atan2(2.0 * s12, s11 - s22);
    s.kmax[v] = static_cast<float>(mean + radius);
    s.kmin[v] = static_cast<float>(mean - radius);
    s.dmax[v] = glm::vec3(std::cos(theta) * e1 + std::sin(theta) * e2);
    s.dmin[v] = glm::vec3(-std::sin(theta) * e1 + std::cos(theta) * e2);
    s.known[v] = 1;
  }
  finish(s);
  return s;
}

void add_normal_noise(TestSurface& s, float fraction, std::uint32_t seed) {
  double edge = 0;
  for (const Triangle& t : s.mesh.triangles)
    edge += glm::length(glm::dvec3(s.mesh.positions[t[0]]) - glm::dvec3(s.mesh.positions[t[1]]));
  edge /= static_cast<double>(std::max<std::size_t>(1, s.mesh.triangle_count()));
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, fraction * edge);
  for (std::size_t i = 0; i < s.mesh.vertex_count(); ++i)
    s.mesh.positions[i] += glm::vec3(gauss(rng) * glm::dvec3(s.mesh.normals[i]));
  s.name +=
      " + noise " + std::to_string(static_cast<int>(std::lround(100 * fraction))) + "% of an edge";
  compute_vertex_normals(s.mesh);
}

CurvatureErrors curvature_errors(const TestSurface& s, const Curvature& c) {
  CurvatureErrors e;
  std::vector<double> kmax_rel, kmin_abs, dir;
  const double k0 = s.kappa_rms;
  for (std::size_t i = 0; i < c.kmin.size(); ++i) {
    if (!std::isfinite(c.kmin[i]) || !std::isfinite(c.kmax[i])) ++e.non_finite;
    if (i >= s.known.size() || !s.known[i]) continue;
    kmax_rel.push_back(std::abs(c.kmax[i] - s.kmax[i]) / std::max<double>(std::abs(s.kmax[i]), k0));
    kmin_abs.push_back(std::abs(c.kmin[i] - s.kmin[i]));
    if (s.kmax[i] - s.kmin[i] > 0.1 * k0) {
      const double cosine = std::min(
          1.0, std::abs(double(glm::dot(glm::normalize(c.dmax[i]), glm::normalize(s.dmax[i])))));
      dir.push_back(std::acos(cosine) * 180.0 / kPi);
    }
  }
  const auto pct = [](std::vector<double>& v, double q) {
    if (v.empty()) return 0.0;
    const std::size_t k =
        std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
  };
  e.count = kmax_rel.size();
  e.kmax_rel_median = pct(kmax_rel, 0.5);
  e.kmax_rel_p95 = pct(kmax_rel, 0.95);
  e.kmin_abs_median = pct(kmin_abs, 0.5);
  e.kmin_abs_p95 = pct(kmin_abs, 0.95);
  e.dir_median = pct(dir, 0.5);
  e.dir_p95 = pct(dir, 0.95);
  return e;
}

Curvature cgal_jet_fitting(const TriMesh& mesh, int degree, int rings) {
  Curvature c;
#ifdef IBFVS_TEST_HAVE_CGAL
  using K = CGAL::Simple_cartesian<double>;
  using Fitting = CGAL::Monge_via_jet_fitting<K>;
  const std::size_t n = mesh.vertex_count();
  std::vector<std::vector<std::uint32_t>> adj(n);
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      adj[t[k]].push_back(t[(k + 1) % 3]);
      adj[t[k]].push_back(t[(k + 2) % 3]);
    }
  c.kmin.assign(n, 0.0f);
  c.kmax.assign(n, 0.0f);
  c.dmin.assign(n, glm::vec3(1, 0, 0));
  c.dmax.assign(n, glm::vec3(0, 1, 0));
  c.normal = mesh.normals;
  const std::size_t needed = static_cast<std::size_t>((degree + 1) * (degree + 2) / 2);
#pragma omp parallel
  {
    std::vector<int> mark(n, -1);
    std::vector<K::Point_3> pts;
    std::vector<std::uint32_t> hood, frontier, next;
#pragma omp for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
      hood.assign(1, static_cast<std::uint32_t>(i));
      mark[i] = static_cast<int>(i);
      frontier = hood;
      for (int ring = 0; ring < 6 && !frontier.empty(); ++ring) {
        if (ring >= rings && hood.size() >= needed) break;
        next.clear();
        for (const std::uint32_t v : frontier)
          for (const std::uint32_t q : adj[v])
            if (mark[q] != static_cast<int>(i)) {
              mark[q] = static_cast<int>(i);
              next.push_back(q);
              hood.push_back(q);
            }
        frontier.swap(next);
      }
      if (hood.size() < needed) continue;
      pts.clear();
      for (const std::uint32_t q : hood) {
        const glm::vec3& p = mesh.positions[q];
        pts.emplace_back(p.x, p.y, p.z);
      }
      Fitting fitting;
      Fitting::Monge_form form =
          fitting(pts.begin(), pts.end(), static_cast<std::size_t>(degree), 2);
      const glm::vec3& nm = mesh.normals[i];
      form.comply_wrt_given_normal(K::Vector_3(nm.x, nm.y, nm.z));
      // CGAL's z = (k1 x^2 + k2 y^2) / 2 along its normal: a convex surface
      // with an outward normal has k < 0, the opposite of Curvature's sign.
      const auto vec = [](const K::Vector_3& v) { return glm::vec3(v.x(), v.y(), v.z()); };
      const float k1 = -static_cast<float>(form.principal_curvatures(0));
      const float k2 = -static_cast<float>(form.principal_curvatures(1));
      const glm::vec3 d1 = vec(form.maximal_principal_direction());
      const glm::vec3 d2 = vec(form.minimal_principal_direction());
      if (k1 >= k2) {
        c.kmax[i] = k1, c.dmax[i] = d1, c.kmin[i] = k2, c.dmin[i] = d2;
      } else {
        c.kmax[i] = k2, c.dmax[i] = d2, c.kmin[i] = k1, c.dmin[i] = d1;
      }
      c.normal[i] = vec(form.normal_direction());
    }
  }
#else
  (void)mesh, (void)degree, (void)rings;
#endif
  return c;
}

}  // namespace ibfvs::test
