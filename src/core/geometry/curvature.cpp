#include "ibfvs/core/geometry/curvature.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include <Eigen/Dense>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "ibfvs/core/support/error.h"

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

// A tangent frame (u, v) for the unit normal n, with u x v = n.
void tangent_frame(const glm::dvec3& n, glm::dvec3& u, glm::dvec3& v) {
  const glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  u = glm::normalize(glm::cross(a, n));
  v = glm::cross(n, u);
}

// The vertices around a centre, ring by ring: reset(centre), then grow()
// once per ring; ids() lists them in ring order, without the centre. Taken
// vertices carry the stamp of the current reset, so nothing is cleared
// between centres.
class Neighbourhood {
 public:
  explicit Neighbourhood(std::size_t vertices) : mark_(vertices, 0) {}

  void reset(std::uint32_t centre) {
    ids_.clear();
    centre_ = centre;
    frontier_begin_ = 0;
    rings_ = 0;
    if (++stamp_ == 0) {  // wrapped: old stamps could match again
      std::fill(mark_.begin(), mark_.end(), 0u);
      stamp_ = 1;
    }
    mark_[centre] = stamp_;
  }
  void grow(const Adjacency& adj) {
    const std::size_t end = ids_.size();
    if (rings_ == 0) push_row(adj, centre_);
    for (std::size_t k = frontier_begin_; k < end; ++k) push_row(adj, ids_[k]);
    frontier_begin_ = end;
    ++rings_;
  }
  [[nodiscard]] const std::vector<std::uint32_t>& ids() const { return ids_; }
  [[nodiscard]] int rings() const { return rings_; }
  /// The last grow() added nobody (a closed component is used up).
  [[nodiscard]] bool exhausted() const { return frontier_begin_ == ids_.size(); }

 private:
  void push_row(const Adjacency& adj, std::uint32_t v) {
    for (std::uint32_t j = adj.start[v]; j < adj.start[v + 1]; ++j) {
      const std::uint32_t q = adj.ids[j];
      if (mark_[q] == stamp_) continue;
      mark_[q] = stamp_;
      ids_.push_back(q);
    }
  }
  std::vector<std::uint32_t> mark_;
  std::vector<std::uint32_t> ids_;
  std::uint32_t centre_ = 0, stamp_ = 0;
  std::size_t frontier_begin_ = 0;
  int rings_ = 0;
};

// One neighbour in the local frame, coordinates divided by the scale h.
struct Sample {
  double x, y, z;  // position
  double sx, sy;   // slopes -a/c, -b/c from its normal
  bool has_slope;
  double w = 1.0;
};

constexpr int unknowns(int degree) {
  return (degree + 1) * (degree + 2) / 2 - 1;  // every monomial of degree 1..d
}

// A fitted jet at the origin: gradient, Hessian (in the scaled frame) and
// the standard error of the Hessian estimated from the fit's residuals.
struct JetFit {
  double g[2] = {0, 0};
  double hess[3] = {0, 0, 0};
  double se = std::numeric_limits<double>::infinity();
  bool ok = false;
};

// Least-squares fit of the jet z = sum c_ij x^i y^j, 1 <= i + j <= Degree, to
// the samples' positions (each weighted by its w) and, with weight
// `slope_weight`, their slopes. The jet passes through the vertex itself: its
// position is the one thing the mesh gives exactly. Monomials in order of
// degree: x y | x^2 xy y^2 | x^3 ... Not ok when the system is rank deficient
// (the neighbours do not span the jet). With `want_se`, also the Hessian's
// standard error. `design` and `rhs` are scratch space.
template <int Degree>
JetFit fit_jet(const std::vector<Sample>& samples, double slope_weight, bool want_se,
               Eigen::MatrixXd& design, Eigen::VectorXd& rhs) {
  constexpr int K = unknowns(Degree);
  using Row = Eigen::Matrix<double, K, 1>;
  JetFit fit;
  // The design matrix, one row per equation.
  Eigen::Index rows = 0;
  for (const Sample& s : samples) rows += (slope_weight > 0.0 && s.has_slope) ? 3 : 1;
  if (rows < K) return fit;
  design.resize(rows, K);
  rhs.resize(rows);
  Eigen::Index row = 0;
  for (const Sample& s : samples) {
    double px[Degree + 1], py[Degree + 1];
    px[0] = py[0] = 1.0;
    for (int k = 1; k <= Degree; ++k) px[k] = px[k - 1] * s.x, py[k] = py[k - 1] * s.y;
    const bool slopes = slope_weight > 0.0 && s.has_slope;
    int col = 0;
    for (int d = 1; d <= Degree; ++d)
      for (int j = 0; j <= d; ++j, ++col) {
        const int i = d - j;  // x^i y^j
        design(row, col) = px[i] * py[j] * s.w;
        if (slopes) {
          design(row + 1, col) = i > 0 ? i * px[i - 1] * py[j] * slope_weight : 0.0;
          design(row + 2, col) = j > 0 ? j * px[i] * py[j - 1] * slope_weight : 0.0;
        }
      }
    rhs(row) = s.z * s.w;
    if (slopes) {
      rhs(row + 1) = s.sx * slope_weight;
      rhs(row + 2) = s.sy * slope_weight;
    }
    row += slopes ? 3 : 1;
  }
  Eigen::Matrix<double, K, K> ata;
  ata.noalias() = design.transpose() * design;
  const Row atb = design.transpose() * rhs;
  // Jacobi scaling, then Cholesky; a tiny pivot means the neighbours do not
  // determine some coefficient (too few, or all on a line or a conic).
  Row scale;
  for (int k = 0; k < K; ++k) {
    const double d = ata(k, k);
    if (!(d > 0.0)) return fit;
    scale(k) = 1.0 / std::sqrt(d);
  }
  const Eigen::Matrix<double, K, K> m = (scale * scale.transpose()).cwiseProduct(ata);
  const Eigen::LLT<Eigen::Matrix<double, K, K>> llt(m);
  if (llt.info() != Eigen::Success) return fit;
  const auto diag = llt.matrixLLT().diagonal();
  if (!(diag.minCoeff() > 1e-6 * diag.maxCoeff())) return fit;
  const Row c = scale.asDiagonal() * llt.solve(scale.asDiagonal() * atb);
  if (!c.allFinite()) return fit;
  fit.g[0] = c(0), fit.g[1] = c(1);
  fit.hess[0] = 2.0 * c(2), fit.hess[1] = c(3), fit.hess[2] = 2.0 * c(4);
  fit.ok = true;
  if (!want_se) return fit;
  // The residuals estimate the noise (and what the jet cannot follow); the
  // Hessian's share of the coefficients' covariance sigma^2 (A^T A)^-1
  // turns it into the Hessian's standard error (Frobenius norm: H11^2 +
  // 2 H12^2 + H22^2, with H11 = 2 c2, H12 = c3, H22 = 2 c4).
  const double rss = (design * c - rhs).squaredNorm();
  const double sigma2 = rss / static_cast<double>(std::max<Eigen::Index>(1, rows - K));
  double var = 0.0;
  for (int k = 2; k <= 4; ++k)
    var += (k == 3 ? 2.0 : 4.0) * scale(k) * scale(k) * llt.solve(Row::Unit(k))(k);
  fit.se = std::sqrt(sigma2 * var);
  return fit;
}

// Fits a jet of degree `degree`, falling back to lower degrees (down to 2,
// then without slopes). Returns the degree used in `used`, 0 when none fitted.
JetFit fit_best(const std::vector<Sample>& samples, int degree, double slope_weight, bool want_se,
                int& used) {
  thread_local Eigen::MatrixXd design;
  thread_local Eigen::VectorXd rhs;
  JetFit f;
  if (degree >= 4 && (f = fit_jet<4>(samples, slope_weight, want_se, design, rhs)).ok)
    return used = 4, f;
  if (degree >= 3 && (f = fit_jet<3>(samples, slope_weight, want_se, design, rhs)).ok)
    return used = 3, f;
  if ((f = fit_jet<2>(samples, slope_weight, want_se, design, rhs)).ok) return used = 2, f;
  if (slope_weight > 0.0 && (f = fit_jet<2>(samples, 0.0, want_se, design, rhs)).ok)
    return used = 2, f;
  return used = 0, f;
}

// The curvature of the graph z = f(x, y) over the frame (u, v, n) at the
// origin, from its gradient g and Hessian (unscaled): the exact principal
// curvatures and directions of the fitted surface, whatever its tilt.
struct PointCurvature {
  double kmin, kmax;
  glm::dvec3 dmin, dmax, normal;
};

PointCurvature graph_curvature(const glm::dvec3& u, const glm::dvec3& v, const glm::dvec3& n,
                               const double g[2], const double hess[3]) {
  const glm::dvec3 xu = u + g[0] * n, xv = v + g[1] * n;
  const glm::dvec3 normal = glm::normalize(glm::cross(xu, xv));
  // An orthonormal tangent basis (e1, e2) with e1 along xu; A maps parameter
  // steps to it: [xu xv] = [e1 e2] A with A upper triangular.
  const glm::dvec3 e1 = glm::normalize(xu), e2 = glm::cross(normal, e1);
  const double a11 = glm::dot(xu, e1), a12 = glm::dot(xv, e1), a22 = glm::dot(xv, e2);
  // Second fundamental form in parameters: X_ij . N = f_ij (n . N).
  const double w = glm::dot(n, normal);
  const double l = hess[0] * w, m = hess[1] * w, nn = hess[2] * w;
  // In the orthonormal basis: A^-T II A^-1, with A^-1 = [[1/a11, -a12/(a11 a22)], [0, 1/a22]].
  const double i11 = 1.0 / a11, i12 = -a12 / (a11 * a22), i22 = 1.0 / a22;
  const double s11 = i11 * i11 * l;
  const double s12 = i11 * (i12 * l + i22 * m);
  const double s22 = i12 * i12 * l + 2.0 * i12 * i22 * m + i22 * i22 * nn;
  // Shape operator -S (outward normals: a convex surface curves away from
  // the normal, f_ij < 0, and has positive curvature).
  const double a = -s11, b = -s12, d = -s22;
  const double mean = 0.5 * (a + d), radius = std::hypot(0.5 * (a - d), b);
  const double theta = 0.5 * std::atan2(2.0 * b, a - d);
  PointCurvature pc;
  pc.kmax = mean + radius;
  pc.kmin = mean - radius;
  pc.dmax = std::cos(theta) * e1 + std::sin(theta) * e2;
  pc.dmin = -std::sin(theta) * e1 + std::cos(theta) * e2;
  pc.normal = normal;
  return pc;
}

// Samples of the neighbours in the frame (u, v, n) around p, scaled by 1/h,
// with slopes from `normals` where given and not tilted past min_cos, and
// Gaussian weights of width `radius` (in units of h; 0: all weights 1).
void make_samples(const TriMesh& mesh, const std::vector<std::uint32_t>& nb,
                  const std::vector<glm::vec3>* normals, const glm::dvec3& p, const glm::dvec3& u,
                  const glm::dvec3& v, const glm::dvec3& n, double h, double min_cos, double radius,
                  std::vector<Sample>& out) {
  out.clear();
  for (const std::uint32_t q : nb) {
    const glm::dvec3 d = (glm::dvec3(mesh.positions[q]) - p) / h;
    Sample s{glm::dot(d, u), glm::dot(d, v), glm::dot(d, n), 0, 0, false, 1.0};
    if (radius > 0.0) s.w = std::exp(-(s.x * s.x + s.y * s.y) / (2.0 * radius * radius));
    if (normals) {
      const glm::dvec3 m((*normals)[q]);
      const double c = glm::dot(m, n);
      if (c > min_cos && std::isfinite(c)) {
        s.sx = -glm::dot(m, u) / c;
        s.sy = -glm::dot(m, v) / c;
        s.has_slope = true;
      }
    }
    out.push_back(s);
  }
}

// The vertices that a vertex's fit uses: `rings` rings, grown (up to 3)
// while there are fewer than `wanted`, without vertices at its position;
// `h` is their mean distance (the fit's length scale).
void gather(const TriMesh& mesh, const Adjacency& adj, std::size_t i, int rings, std::size_t wanted,
            Neighbourhood& hood, std::vector<std::uint32_t>& nb, double& h) {
  const glm::dvec3 p(mesh.positions[i]);
  hood.reset(static_cast<std::uint32_t>(i));
  nb.clear();
  h = 0.0;
  std::size_t taken = 0;
  do {
    hood.grow(adj);
    for (std::size_t k = taken; k < hood.ids().size(); ++k) {
      const std::uint32_t q = hood.ids()[k];
      const double dist = glm::length(glm::dvec3(mesh.positions[q]) - p);
      if (!(dist > 0.0) || !std::isfinite(dist)) continue;
      h += dist;
      nb.push_back(q);
    }
    taken = hood.ids().size();
    if (hood.rings() >= rings && nb.size() >= wanted) break;
  } while (hood.rings() < 3 && !hood.exhausted());
  if (!nb.empty()) h /= static_cast<double>(nb.size());
}

// A vertex's fit turned into curvature; not ok when nothing fitted or the
// fit tilts the normal wildly (the neighbours fold over: a thin part).
struct Estimate {
  PointCurvature pc;
  double se = std::numeric_limits<double>::infinity();  // standard error, 1/length
  int degree = 0;
  bool ok = false;
};

Estimate estimate(const std::vector<Sample>& samples, int degree, double slope_weight, bool want_se,
                  double h, const glm::dvec3& u, const glm::dvec3& v, const glm::dvec3& n) {
  Estimate e;
  if (samples.empty()) return e;
  JetFit f = fit_best(samples, degree, slope_weight, want_se, e.degree);
  if (!f.ok) return e;
  for (double& x : f.hess) x /= h;
  e.pc = graph_curvature(u, v, n, f.g, f.hess);
  e.se = f.se / h;
  e.ok = glm::dot(e.pc.normal, n) > 0.5 && std::isfinite(e.pc.kmin) && std::isfinite(e.pc.kmax);
  return e;
}

// The Frobenius norm of the difference of two curvature tensors
// kmax dmax dmax^T + kmin dmin dmin^T.
double tensor_distance(const PointCurvature& a, const PointCurvature& b) {
  const auto tensor = [](const PointCurvature& p) {
    return p.kmax * glm::outerProduct(p.dmax, p.dmax) + p.kmin * glm::outerProduct(p.dmin, p.dmin);
  };
  const glm::dmat3 d = tensor(a) - tensor(b);
  double sum = 0.0;
  for (int col = 0; col < 3; ++col) sum += glm::dot(d[col], d[col]);
  return std::sqrt(sum);
}

// Above this median ratio of the quartic-cubic difference to the quartic's
// standard error the mesh counts as exact (measured: 20 to 500 on jittered,
// random and Loop-limit meshes, 9 at noise of 0.03% of an edge, 3 at 0.1%
// and more; bench/curvature_accuracy).
constexpr double kQuarticRatio = 6.0;

// A quartic whose normal leaves the cubic's by more than this (cosine of
// 10 degrees: on exact surfaces they agree within a fraction of a degree)
// has followed a crease or a thin part: the cubic with normals is used.
const double kQuarticTilt = std::cos(10.0 * std::numbers::pi / 180.0);

glm::dvec3 unit_or(const glm::vec3& a, const glm::dvec3& fallback) {
  const glm::dvec3 d(a);
  const double len = glm::length(d);
  return len > 0.5 && std::isfinite(len) ? d / len : fallback;
}

}  // namespace

Curvature compute_curvature(const TriMesh& mesh, const CurvatureOptions& options) {
  const std::size_t n = mesh.vertex_count();
  if (mesh.normals.size() != n) throw InputError("curvature: the mesh needs vertex normals");
  const Adjacency adj = build_adjacency(mesh);
  const int rings = std::clamp(options.rings, 1, 3);
  const std::size_t wanted = static_cast<std::size_t>(unknowns(4) + 3);
  const double min_cos = options.min_normal_cosine;
  const double radius = std::max(0.0f, options.weight_radius);
  const bool automatic = options.fit == CurvatureFit::automatic;
  // The vertices that decide the automatic choice: about 4000.
  const std::size_t stride = std::max<std::size_t>(1, n / 4000);

  struct Scratch {
    explicit Scratch(std::size_t vertices) : hood(vertices) {}
    Neighbourhood hood;
    std::vector<std::uint32_t> nb;
    std::vector<Sample> samples;
  };
  // A jet of `degree` fitted around vertex i in the frame of `normal`, with
  // the given Gaussian weights and slope equations from `slopes` (or none).
  const auto fit_at = [&](std::size_t i, const glm::dvec3& normal, int degree, double weights,
                          const std::vector<glm::vec3>* slopes, bool want_se, Scratch& s) {
    glm::dvec3 u, v;
    tangent_frame(normal, u, v);
    double h = 0.0;
    gather(mesh, adj, i, rings, wanted, s.hood, s.nb, h);
    make_samples(mesh, s.nb, slopes, glm::dvec3(mesh.positions[i]), u, v, normal, h, min_cos,
                 weights, s.samples);
    Estimate e = estimate(s.samples, degree, slopes ? 1.0 : 0.0, want_se, h, u, v, normal);
    if (!e.ok) e.pc = PointCurvature{0, 0, v, u, normal};  // flat, directions in the frame
    return e;
  };
  // The quartic jet of the positions, in the frame of the mesh's normal (the
  // jet's own gradient corrects it).
  const auto quartic_jet = [&](std::size_t i, bool want_se, Scratch& s) {
    return fit_at(i, unit_or(mesh.normals[i], glm::dvec3(0, 0, 1)), 4, radius, nullptr, want_se, s);
  };

  // Pass 1: the normal of a cubic jet of the positions at every vertex (a
  // cubic averages noise better than a quartic): the frames and slopes of
  // the cubic fit with normals, and the check on the quartic's normal.
  std::vector<glm::vec3> first_normals(n);
  std::vector<Estimate> sampled(automatic ? (n + stride - 1) / stride : 0);
#pragma omp parallel
  {
    Scratch s(n);
#pragma omp for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec3 normal = unit_or(mesh.normals[i], glm::dvec3(0, 0, 1));
      const Estimate cubic = fit_at(i, normal, 3, 0.0, nullptr, false, s);
      first_normals[i] = glm::vec3(cubic.ok ? cubic.pc.normal : normal);
      if (automatic && i % stride == 0) sampled[i / stride] = quartic_jet(i, true, s);
    }
  }

  // The cubic fit with normals (Goldfeather and Interrante's) of vertex i,
  // in the frame of its first normal, with its neighbours' as slopes.
  const auto cubic_with_normals = [&](std::size_t i, Scratch& s) {
    const glm::dvec3 normal =
        unit_or(first_normals[i], unit_or(mesh.normals[i], glm::dvec3(0, 0, 1)));
    return fit_at(i, normal, 3, 0.0, &first_normals, false, s);
  };

  // Which fit: on exact surfaces the quartic and the cubic differ by the
  // cubic's truncation error, tens to hundreds of times the quartic's
  // standard error (estimated from its residuals); where noise dominates by
  // a few times only. The median ratio over a sample of vertices decides
  // for the whole mesh (a noisy scan is noisy everywhere; a per-vertex
  // choice follows the noise of the estimates themselves).
  Curvature c;
  c.fit = options.fit;
  if (automatic) {
    std::vector<double> ratios;
#pragma omp parallel
    {
      Scratch s(n);
      std::vector<double> mine;
#pragma omp for schedule(dynamic, 64) nowait
      for (std::size_t k = 0; k < sampled.size(); ++k) {
        if (!sampled[k].ok) continue;
        const Estimate b = cubic_with_normals(k * stride, s);
        if (!b.ok) continue;
        const double d = tensor_distance(sampled[k].pc, b.pc);
        mine.push_back(sampled[k].se > 0.0 ? d / sampled[k].se
                                           : std::numeric_limits<double>::infinity());
      }
#pragma omp critical
      ratios.insert(ratios.end(), mine.begin(), mine.end());
    }
    double median = std::numeric_limits<double>::infinity();
    if (!ratios.empty()) {
      const auto mid = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
      std::nth_element(ratios.begin(), mid, ratios.end());
      median = *mid;
    }
    c.noise_ratio = static_cast<float>(std::min(median, 1e9));
    c.fit = median > kQuarticRatio ? CurvatureFit::quartic : CurvatureFit::cubic_with_normals;
  }

  // Pass 2: the chosen fit at every vertex; where the quartic does not fit
  // or tilts away from the first normal, the cubic with normals.
  c.kmin.assign(n, 0.0f);
  c.kmax.assign(n, 0.0f);
  c.dmin.assign(n, glm::vec3(0));
  c.dmax.assign(n, glm::vec3(0));
  c.normal.assign(n, glm::vec3(0));
  std::size_t fallbacks = 0, quartics = 0;
#pragma omp parallel reduction(+ : fallbacks, quartics)
  {
    Scratch s(n);
#pragma omp for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
      Estimate e;
      if (c.fit == CurvatureFit::quartic) {
        e = automatic && i % stride == 0 ? sampled[i / stride] : quartic_jet(i, false, s);
        if (e.ok && glm::dot(e.pc.normal, glm::dvec3(first_normals[i])) > kQuarticTilt)
          ++quartics;
        else
          e = cubic_with_normals(i, s);
      } else {
        e = cubic_with_normals(i, s);
      }
      fallbacks += (!e.ok || e.degree < 3) ? 1 : 0;
      const PointCurvature& pc = e.pc;
      c.kmax[i] = static_cast<float>(pc.kmax);
      c.kmin[i] = static_cast<float>(pc.kmin);
      c.dmax[i] = glm::vec3(pc.dmax);
      c.dmin[i] = glm::vec3(pc.dmin);
      c.normal[i] = glm::vec3(pc.normal);
      if (!std::isfinite(c.kmax[i]) || !std::isfinite(c.kmin[i])) c.kmax[i] = c.kmin[i] = 0.0f;
    }
  }
  c.fallback_vertices = fallbacks;
  c.quartic_vertices = quartics;
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
