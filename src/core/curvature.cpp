#include "ibfvs/core/curvature.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <glm/geometric.hpp>

#include "ibfvs/core/error.h"

namespace ibfvs {
namespace {

// Vertex neighbours in compressed rows: the neighbours of v are
// ids[start[v]] .. ids[start[v + 1] - 1], sorted, without v itself.
struct Adjacency {
  std::vector<std::uint32_t> start;
  std::vector<std::uint32_t> ids;
};

Adjacency build_adjacency(const TriMesh& mesh) {
  const std::size_t n = mesh.vertex_count();
  std::vector<std::uint32_t> count(n + 1, 0);
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) count[t[k] + 1] += 2;
  for (std::size_t v = 0; v < n; ++v) count[v + 1] += count[v];
  std::vector<std::uint32_t> ids(count[n]);
  std::vector<std::uint32_t> fill(count.begin(), count.end() - 1);
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      ids[fill[t[k]]++] = t[(k + 1) % 3];
      ids[fill[t[k]]++] = t[(k + 2) % 3];
    }
  // Sort and deduplicate each row in place, compacting as we go.
  Adjacency adj;
  adj.start.assign(n + 1, 0);
  std::size_t out = 0;
  for (std::size_t v = 0; v < n; ++v) {
    const auto first = ids.begin() + count[v], last = ids.begin() + count[v + 1];
    std::sort(first, last);
    const auto end = std::unique(first, last);
    adj.start[v] = static_cast<std::uint32_t>(out);
    for (auto it = first; it != end; ++it)
      if (*it != v) ids[out++] = *it;
  }
  adj.start[n] = static_cast<std::uint32_t>(out);
  ids.resize(out);
  adj.ids = std::move(ids);
  return adj;
}

// A tangent frame (u, v) for the unit normal n.
void tangent_frame(const glm::dvec3& n, glm::dvec3& u, glm::dvec3& v) {
  const glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  u = glm::normalize(glm::cross(a, n));
  v = glm::cross(n, u);
}

// One neighbour in the local frame, coordinates divided by the scale h.
struct Sample {
  double x, y, z;  // position
  double sx, sy;   // slopes -a/c, -b/c from its normal
  bool has_slope;
};

// Least-squares fit of z(x, y) to the samples. `linear` adds the terms a x + b y
// (the first pass that tilts the normal); `cubic` the third-order terms.
// Unknowns, in order: [a b] A B C [D E F G]. Returns false when the system
// has too few equations or is rank deficient.
template <int K>
bool fit(const std::vector<Sample>& samples, bool linear, bool cubic, bool slopes,
         Eigen::Matrix<double, K, 1>& x) {
  using Row = Eigen::Matrix<double, K, 1>;
  Eigen::Matrix<double, K, K> ata = Eigen::Matrix<double, K, K>::Zero();
  Row atb = Row::Zero();
  int rows = 0;
  const auto add = [&](const Row& r, double rhs) {
    ata.noalias() += r * r.transpose();
    atb.noalias() += r * rhs;
    ++rows;
  };
  const int o = linear ? 2 : 0;
  for (const Sample& s : samples) {
    Row r = Row::Zero();
    if (linear) r.template head<2>() << s.x, s.y;
    r(o + 0) = 0.5 * s.x * s.x;
    r(o + 1) = s.x * s.y;
    r(o + 2) = 0.5 * s.y * s.y;
    if (cubic)
      r.template segment<4>(o + 3) << s.x * s.x * s.x, s.x * s.x * s.y, s.x * s.y * s.y,
          s.y * s.y * s.y;
    add(r, s.z);
    if (!slopes || !s.has_slope) continue;
    Row rx = Row::Zero(), ry = Row::Zero();
    if (linear) {
      rx(0) = 1.0;
      ry(1) = 1.0;
    }
    rx(o + 0) = s.x;
    rx(o + 1) = s.y;
    ry(o + 1) = s.x;
    ry(o + 2) = s.y;
    if (cubic) {
      rx.template segment<4>(o + 3) << 3 * s.x * s.x, 2 * s.x * s.y, s.y * s.y, 0.0;
      ry.template segment<4>(o + 3) << 0.0, s.x * s.x, 2 * s.x * s.y, 3 * s.y * s.y;
    }
    add(rx, s.sx);
    add(ry, s.sy);
  }
  if (rows < K) return false;
  const Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix<double, K, K>> cod(ata);
  if (cod.rank() < K) return false;
  x = cod.solve(atb);
  return x.allFinite();
}

// Samples of the neighbours of p in the frame (u, v, n), scaled by 1/h.
void make_samples(const TriMesh& mesh, const std::vector<std::uint32_t>& nb, const glm::dvec3& p,
                  const glm::dvec3& u, const glm::dvec3& v, const glm::dvec3& n, double h,
                  double min_cos, std::vector<Sample>& out) {
  out.clear();
  for (const std::uint32_t q : nb) {
    const glm::dvec3 d = (glm::dvec3(mesh.positions[q]) - p) / h;
    Sample s{glm::dot(d, u), glm::dot(d, v), glm::dot(d, n), 0, 0, false};
    const glm::dvec3 m(mesh.normals[q]);
    const double c = glm::dot(m, n);
    if (c > min_cos && std::isfinite(c)) {
      s.sx = -glm::dot(m, u) / c;
      s.sy = -glm::dot(m, v) / c;
      s.has_slope = true;
    }
    out.push_back(s);
  }
}

}  // namespace

Curvature compute_curvature(const TriMesh& mesh, const CurvatureOptions& options) {
  const std::size_t n = mesh.vertex_count();
  if (mesh.normals.size() != n) throw InputError("curvature: the mesh needs vertex normals");
  const Adjacency adj = build_adjacency(mesh);
  Curvature c;
  c.kmin.assign(n, 0.0f);
  c.kmax.assign(n, 0.0f);
  c.dmin.assign(n, glm::vec3(0));
  c.dmax.assign(n, glm::vec3(0));
  c.normal.assign(n, glm::vec3(0));
  std::size_t fallbacks = 0;

#pragma omp parallel reduction(+ : fallbacks)
  {
    std::vector<std::uint32_t> nb;
    std::vector<Sample> samples;
#pragma omp for schedule(dynamic, 512)
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec3 p(mesh.positions[i]);
      glm::dvec3 normal(mesh.normals[i]);
      if (!(glm::length(normal) > 0.5)) normal = glm::dvec3(0, 0, 1);
      normal = glm::normalize(normal);

      // The 1-ring, widened to the 2-ring when it is small; coincident
      // vertices say nothing and would only make the scale zero.
      nb.assign(adj.ids.begin() + adj.start[i], adj.ids.begin() + adj.start[i + 1]);
      if (static_cast<int>(nb.size()) < options.min_neighbours) {
        const std::size_t ring1 = nb.size();
        for (std::size_t k = 0; k < ring1; ++k)
          for (std::uint32_t j = adj.start[nb[k]]; j < adj.start[nb[k] + 1]; ++j)
            if (adj.ids[j] != i) nb.push_back(adj.ids[j]);
        std::sort(nb.begin(), nb.end());
        nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
      }
      double h = 0.0;
      std::erase_if(nb, [&](std::uint32_t q) {
        const double d = glm::length(glm::dvec3(mesh.positions[q]) - p);
        if (!(d > 0.0)) return true;
        h += d;
        return false;
      });
      glm::dvec3 u, v;
      tangent_frame(normal, u, v);
      double k_uu = 0, k_uv = 0, k_vv = 0;  // the Weingarten matrix, unscaled
      bool ok = false;
      if (!nb.empty()) {
        h /= static_cast<double>(nb.size());
        const double min_cos = options.min_normal_cosine;
        if (options.refine_normals) {
          make_samples(mesh, nb, p, u, v, normal, h, min_cos, samples);
          Eigen::Matrix<double, 9, 1> x;
          if (fit<9>(samples, true, true, true, x)) {
            const glm::dvec3 tilted = glm::normalize(normal - x(0) * u - x(1) * v);
            if (glm::dot(tilted, normal) > 0.5) normal = tilted;  // ignore wild tilts
            tangent_frame(normal, u, v);
          }
        }
        make_samples(mesh, nb, p, u, v, normal, h, min_cos, samples);
        Eigen::Matrix<double, 7, 1> cubic;
        Eigen::Matrix<double, 3, 1> quad;
        if (fit<7>(samples, false, true, true, cubic)) {
          k_uu = cubic(0), k_uv = cubic(1), k_vv = cubic(2);
          ok = true;
        } else if (fit<3>(samples, false, false, true, quad) ||
                   fit<3>(samples, false, false, false, quad)) {
          k_uu = quad(0), k_uv = quad(1), k_vv = quad(2);
          ok = true;
          ++fallbacks;
        }
        k_uu /= h, k_uv /= h, k_vv /= h;
      }
      if (!ok) {
        k_uu = k_uv = k_vv = 0.0;
        ++fallbacks;
      }
      // Shape operator S = -W (outward normals: a convex surface curves away
      // from n, so z < 0 and W < 0). Eigen-decomposition of [[a, b], [b, d]].
      const double a = -k_uu, b = -k_uv, d = -k_vv;
      const double mean = 0.5 * (a + d), radius = std::hypot(0.5 * (a - d), b);
      const double theta = 0.5 * std::atan2(2.0 * b, a - d);
      const glm::dvec3 e_max = std::cos(theta) * u + std::sin(theta) * v;
      const glm::dvec3 e_min = -std::sin(theta) * u + std::cos(theta) * v;
      c.kmax[i] = static_cast<float>(mean + radius);
      c.kmin[i] = static_cast<float>(mean - radius);
      c.dmax[i] = glm::vec3(e_max);
      c.dmin[i] = glm::vec3(e_min);
      c.normal[i] = glm::vec3(normal);
      if (!std::isfinite(c.kmax[i]) || !std::isfinite(c.kmin[i])) {
        c.kmax[i] = c.kmin[i] = 0.0f;
        ++fallbacks;
      }
    }
  }
  c.fallback_vertices = fallbacks;
  return c;
}

void store_curvature(TriMesh& mesh, const Curvature& c, bool refined_normals) {
  if (refined_normals) mesh.normals = c.normal;
  mesh.scalars["kmin"] = c.kmin;
  mesh.scalars["kmax"] = c.kmax;
  const char* axes = "xyz";
  for (int k = 0; k < 3; ++k) {
    auto& mn = mesh.scalars[std::string("dmin") + axes[k]];
    auto& mx = mesh.scalars[std::string("dmax") + axes[k]];
    mn.resize(c.dmin.size());
    mx.resize(c.dmax.size());
    for (std::size_t i = 0; i < c.dmin.size(); ++i) {
      mn[i] = c.dmin[i][k];
      mx[i] = c.dmax[i][k];
    }
  }
}

Curvature mesh_curvature(const TriMesh& mesh) {
  const std::size_t n = mesh.vertex_count();
  const auto stored = [&](const char* name) -> const std::vector<float>* {
    const auto it = mesh.scalars.find(name);
    return it != mesh.scalars.end() && it->second.size() == n ? &it->second : nullptr;
  };
  const char* names[8] = {"kmin", "kmax", "dminx", "dminy", "dminz", "dmaxx", "dmaxy", "dmaxz"};
  const std::vector<float>* s[8];
  for (int k = 0; k < 8; ++k)
    if (!(s[k] = stored(names[k])) || mesh.normals.size() != n) return compute_curvature(mesh);
  Curvature c;
  c.kmin = *s[0];
  c.kmax = *s[1];
  c.dmin.resize(n);
  c.dmax.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    c.dmin[i] = {(*s[2])[i], (*s[3])[i], (*s[4])[i]};
    c.dmax[i] = {(*s[5])[i], (*s[6])[i], (*s[7])[i]};
  }
  c.normal = mesh.normals;
  return c;
}

std::vector<glm::vec3> smooth_line_field(const TriMesh& mesh, const std::vector<glm::vec3>& normals,
                                         std::vector<glm::vec3> directions, int iterations) {
  const std::size_t n = mesh.vertex_count();
  if (directions.size() != n || normals.size() != n || iterations <= 0) return directions;
  // Each undirected edge once (as the smaller index first), so every vertex
  // sees each neighbour once however many triangles share the edge.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<glm::vec3> sum(n);
  for (int it = 0; it < iterations; ++it) {
    sum = directions;
    for (const auto& [a, b] : edges) {
      const glm::vec3 da = directions[a], db = directions[b];
      const float s = glm::dot(da, db) < 0.0f ? -1.0f : 1.0f;
      sum[a] += s * db;
      sum[b] += s * da;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const glm::vec3& nrm = normals[i];
      const glm::vec3 t = sum[i] - glm::dot(sum[i], nrm) * nrm;
      const float len = glm::length(t);
      if (len > 1e-6f) directions[i] = t / len;
    }
  }
  return directions;
}

}  // namespace ibfvs
