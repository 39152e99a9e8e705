#pragma once
// Exact skin-friction fields on a sphere and a torus whose features are known
// in closed form, and the measures the topology tests hold the finder to
// (issue 73): every critical point within 0.03 with its kind and no other,
// each line within 0.01 (mean distance) covering at least 90 % of its true
// length, and no line of either kind elsewhere longer than 5 % of the true
// lines. The bodies are of unit size (a unit sphere, a torus of radius 1).
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/fields/topology.h"
#include "ibfvs/core/mesh/procedural.h"

namespace ibfvs::exact {

inline constexpr double kPi = 3.14159265358979323846;

inline double mean_edge(const TriMesh& m) {
  double sum = 0.0;
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k) sum += glm::length(m.positions[t[k]] - m.positions[t[(k + 1) % 3]]);
  return sum / (3.0 * static_cast<double>(m.triangles.size()));
}

/// Every vertex moved by up to a fifth of an edge, then back onto the surface
/// by `back`: no answer falls on a vertex by construction.
template <class Back>
void jitter(TriMesh& m, Back back, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(-1.0f, 1.0f);
  const float amount = 0.2f * static_cast<float>(mean_edge(m));
  for (glm::vec3& p : m.positions) {
    // C++ leaves the order of a call's arguments open (GCC evaluates the last
    // first, clang the first): drawn one by one, z, y, x, each mesh is the
    // same with any compiler (and the one the bounds were first met on).
    const float z = d(rng), y = d(rng), x = d(rng);
    p = back(p + amount * glm::vec3(x, y, z));
  }
}

/// The icosphere of `level` (5120 triangles at 4), jittered.
inline TriMesh sphere(int level, unsigned seed = 7) {
  TriMesh m = make_globe(level);
  jitter(
      m, [](glm::vec3 p) { return glm::normalize(p); }, seed);
  m.normals = m.positions;
  return m;
}

inline glm::vec3 onto_torus(glm::vec3 p) {  // the nearest point of the torus R 1, r 0.35, axis +Y
  const glm::vec3 ring = glm::normalize(glm::vec3(p.x, 0.0f, p.z));
  return ring + 0.35f * glm::normalize(p - ring);
}

inline TriMesh torus(int segments, int sides, unsigned seed = 11) {
  TriMesh m = make_torus(1.0f, 0.35f, segments, sides);
  jitter(m, onto_torus, seed);
  return m;
}

/// Each vector scaled by a factor of its own, uniform in [0.7, 1.3]: no
/// skin-friction line's path changes, only the speed along it.
inline std::vector<glm::vec3> scaled_at_random(std::vector<glm::vec3> v, unsigned seed = 3) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(0.7f, 1.3f);
  for (glm::vec3& x : v) x *= d(rng);
  return v;
}

// ---- the fields, and their truths

struct TruePoint {
  glm::dvec3 at;
  CriticalKind kind;
};

struct TrueLine {
  LineKind kind;
  std::vector<glm::dvec3> points;  ///< dense, in order
  std::string what;
};

struct Truth {
  std::vector<TruePoint> points;
  std::vector<TrueLine> lines;
};

/// A field of the unit sphere, its value at a point on it (the unit normal).
using SphereField = std::function<glm::dvec3(const glm::dvec3& n)>;

inline std::vector<glm::vec3> on_mesh(const TriMesh& m, const SphereField& f) {
  std::vector<glm::vec3> v;
  for (const glm::vec3& p : m.positions) v.push_back(glm::vec3(f(glm::normalize(glm::dvec3(p)))));
  return v;
}

inline glm::dvec3 tangent(const glm::dvec3& v, const glm::dvec3& n) {
  return v - glm::dot(v, n) * n;
}

/// The axes of the sphere's fields: a tilted, off every grid's symmetry.
struct Axes {
  glm::dvec3 a, b, c;
};
inline Axes axes() {
  const glm::dvec3 a = glm::normalize(glm::dvec3(0.3, 0.2, 0.93));
  const glm::dvec3 b = glm::normalize(glm::cross(a, glm::dvec3(0.6, -0.7, 0.1)));
  return {a, b, glm::cross(a, b)};
}

/// H = a.n + 0.3 (b.n)^2 - 0.3: its zero level is a closed curve that is not
/// a circle (the sphere cut by a parabolic cylinder), off every great
/// circle; H has one maximum (n = a) and one minimum (n = -a).
inline double wavy_h(const glm::dvec3& n) {
  const Axes x = axes();
  const double yb = glm::dot(x.b, n);
  return glm::dot(x.a, n) + 0.3 * yb * yb - 0.3;
}
inline glm::dvec3 wavy_gradient(const glm::dvec3& n) {  // on the sphere
  const Axes x = axes();
  return tangent(x.a + 0.6 * glm::dot(x.b, n) * x.b, n);
}

/// The curve H = 0, densely: for each angle about a, the polar angle where
/// H is zero (H falls monotonically from the maximum at a to the minimum).
inline std::vector<glm::dvec3> wavy_curve(int samples = 4000) {
  const Axes x = axes();
  std::vector<glm::dvec3> out;
  for (int i = 0; i < samples; ++i) {
    const double psi = 2.0 * kPi * i / samples;
    const auto at = [&](double theta) {
      return std::cos(theta) * x.a + std::sin(theta) * (std::cos(psi) * x.b + std::sin(psi) * x.c);
    };
    double lo = 0.0, hi = kPi;
    for (int k = 0; k < 80; ++k) {
      const double mid = 0.5 * (lo + hi);
      (wavy_h(at(mid)) > 0.0 ? lo : hi) = mid;
    }
    out.push_back(at(0.5 * (lo + hi)));
  }
  return out;
}

/// Turning along the level curves of H and pulled onto H = 0 at rate k: the
/// curve is a closed orbit, attracting for k > 0 (a closed separation line),
/// repelling for k < 0 (attachment); the flow spirals out of H's maximum and
/// minimum (repelling foci) onto it, or the reverse.
inline SphereField wavy_cycle(double k) {
  return [k](const glm::dvec3& n) {
    const glm::dvec3 g = wavy_gradient(n);
    return glm::cross(n, g) - k * wavy_h(n) * g;
  };
}

inline Truth wavy_cycle_truth(double k) {
  const Axes x = axes();
  Truth t;
  const bool attracting = k > 0.0;
  t.points = {{x.a, attracting ? CriticalKind::RepellingFocus : CriticalKind::AttractingFocus},
              {-x.a, attracting ? CriticalKind::RepellingFocus : CriticalKind::AttractingFocus}};
  t.lines = {{attracting ? LineKind::Separation : LineKind::Attachment, wavy_curve(),
              "the closed orbit H = 0"}};
  return t;
}

/// Open separation and attachment: the same closed curve H = 0, its
/// neighbours pulled onto it where c.n > 0 and pushed off it where c.n < 0
/// (the curve is symmetric under c -> -c, so what one half gathers the other
/// spreads: no closed orbit attracts). The half with c.n > 0 is a separation
/// line that starts and ends at no critical point, the other half an
/// attachment line; a pull of H^2 off the extremes makes them repelling foci
/// without touching the curve.
inline SphereField wavy_open() {
  return [](const glm::dvec3& n) {
    const Axes x = axes();
    const glm::dvec3 g = wavy_gradient(n);
    const double h = wavy_h(n);
    const double k = 2.0 * glm::dot(x.c, n) + 0.5 * h * h;
    return glm::cross(n, g) - k * h * g;
  };
}

inline Truth wavy_open_truth() {
  const Axes x = axes();
  Truth t;
  t.points = {{x.a, CriticalKind::RepellingFocus}, {-x.a, CriticalKind::RepellingFocus}};
  const std::vector<glm::dvec3> curve = wavy_curve();
  // The two halves, each in order, from where c.n changes sign.
  std::size_t start = 0;
  for (std::size_t i = 0; i < curve.size(); ++i)
    if (glm::dot(x.c, curve[i]) <= 0.0 && glm::dot(x.c, curve[(i + 1) % curve.size()]) > 0.0)
      start = (i + 1) % curve.size();
  TrueLine sep{LineKind::Separation, {}, "the half of H = 0 with c.n > 0"};
  TrueLine att{LineKind::Attachment, {}, "the half of H = 0 with c.n < 0"};
  for (std::size_t k = 0; k < curve.size(); ++k) {
    const glm::dvec3& p = curve[(start + k) % curve.size()];
    (glm::dot(x.c, p) > 0.0 ? sep : att).points.push_back(p);
  }
  t.lines = {sep, att};
  return t;
}

/// The height along the axis `a` on the sphere, flowing down: from the
/// maximum (a repelling node at a) to the minimum (an attracting node at
/// -a); every skin-friction line a meridian, none special.
inline SphereField height_down() {
  return [](const glm::dvec3& n) { return -tangent(axes().a, n); };
}

inline Truth height_down_truth() {
  return {{{axes().a, CriticalKind::RepellingNode}, {-axes().a, CriticalKind::AttractingNode}}, {}};
}

/// Axisymmetric separation about `a`: the flow runs along the meridians from
/// both poles onto the circle a.n = -0.3, where it vanishes: a separation
/// line of zeros (as the wall shear on a sphere at Re = 100 all round its
/// separation ring), off the equator. `swirl` adds a turning about a that
/// changes sign round the circle (as a 3-D solver's round-off does), which
/// breaks the line of zeros into saddles and nodes along it.
inline SphereField ring_of_zeros(double swirl = 0.0) {
  return [swirl](const glm::dvec3& n) {
    const Axes x = axes();
    const double z = glm::dot(x.a, n);
    const glm::dvec3 meridional = -(z + 0.3) * tangent(x.a, n);
    const double off_axis = 1.0 - z * z;  // smooth at the poles
    return meridional + swirl * off_axis * off_axis *
                            std::sin(5.0 * std::atan2(glm::dot(x.c, n), glm::dot(x.b, n))) *
                            glm::cross(x.a, n);
  };
}

inline Truth ring_truth() {
  const Axes x = axes();
  Truth t;
  t.points = {{x.a, CriticalKind::RepellingNode}, {-x.a, CriticalKind::RepellingNode}};
  TrueLine l{LineKind::Separation, {}, "the circle a.n = -0.3"};
  const double r = std::sqrt(1.0 - 0.09);
  for (int i = 0; i <= 4000; ++i) {
    const double psi = 2.0 * kPi * i / 4000.0;
    l.points.push_back(-0.3 * x.a + r * (std::cos(psi) * x.b + std::sin(psi) * x.c));
  }
  t.lines = {l};
  return t;
}

// ---- a plate: the square [-0.5, 0.5]^2 in z = 0, its inside vertices
// jittered in the plane. A curved separation line y = g(x) that starts at
// no critical point: the flow runs along x, parallel to the curve g, until
// its neighbours are pulled onto it from x = -0.35 on (fully from -0.15),
// and leaves across the plate's edge at x = 0.5.

inline TriMesh plate(int n, unsigned seed = 5) {
  TriMesh m = make_square(0.5f, n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(-1.0f, 1.0f);
  const float amount = 0.2f * (1.0f / static_cast<float>(n));
  for (glm::vec3& p : m.positions) {
    if (!(std::abs(p.x) < 0.499f && std::abs(p.y) < 0.499f)) continue;
    const float y = d(rng), x = d(rng);  // one by one, as jitter() draws
    p += amount * glm::vec3(x, y, 0.0f);
  }
  return m;
}

inline double plate_g(double x) {
  return 0.12 * std::sin(2.5 * x);
}
inline double plate_pull(double x) {  // 0 before -0.35, 8 after -0.15, smoothly between
  const double s = std::clamp((x + 0.35) / 0.2, 0.0, 1.0);
  return 8.0 * s * s * (3.0 - 2.0 * s);
}

/// The pull onto the curve, -k(x) 0.1 tanh(d / 0.1) at a distance d from
/// it, is strongest on the curve and converges everywhere (no band's flank
/// where the flow spreads).
inline std::vector<glm::vec3> plate_field(const TriMesh& m) {
  std::vector<glm::vec3> v;
  for (const glm::vec3& p : m.positions) {
    const double x = p.x, d = p.y - plate_g(x);
    const double slope = 0.3 * std::cos(2.5 * x);
    v.emplace_back(1.0f, static_cast<float>(slope - plate_pull(x) * 0.1 * std::tanh(d / 0.1)),
                   0.0f);
  }
  return v;
}

/// The line from where the pull is a quarter on (x = -0.3) to the plate's edge.
inline Truth plate_truth() {
  Truth t;
  TrueLine l{LineKind::Separation, {}, "the curve y = g(x), x from -0.3"};
  for (int i = 0; i <= 2000; ++i) {
    const double x = -0.3 + 0.8 * i / 2000.0;
    l.points.emplace_back(x, plate_g(x), 0.0);
  }
  t.lines = {l};
  return t;
}

// ---- the torus: R = 1, r = 0.35, axis +Y; points (R + r cos v)(cos u, 0,
// sin u) + r sin v (0, 1, 0) in a frame turned so that u = 0 is `dir`.

inline glm::dvec3 torus_dir() {
  return glm::normalize(glm::dvec3(1.0, 0.0, 0.137));
}

inline glm::dvec3 torus_point(double u, double v) {
  const glm::dvec3 d = torus_dir(), e = glm::cross(glm::dvec3(0, 1, 0), d);  // e: u = 90 degrees
  const double rr = 1.0 + 0.35 * std::cos(v);
  return rr * (std::cos(u) * d + std::sin(u) * e) + 0.35 * std::sin(v) * glm::dvec3(0, 1, 0);
}

/// The height along `dir` flowing down: a maximum (repelling node) at the
/// outside of u = 0, saddles inside at u = 0 and u = pi, a minimum outside at
/// u = pi.
inline std::vector<glm::vec3> torus_height_down(const TriMesh& m) {
  std::vector<glm::vec3> v;
  for (const glm::vec3& p : m.positions) {
    const glm::vec3 ring = glm::normalize(glm::vec3(p.x, 0.0f, p.z));
    const glm::dvec3 n = glm::normalize(glm::dvec3(p - ring));
    v.push_back(glm::vec3(-tangent(torus_dir(), n)));
  }
  return v;
}

inline std::vector<glm::dvec3> torus_curve(double u0, double u1, double v0, double v1,
                                           int n = 2000) {
  std::vector<glm::dvec3> out;
  for (int i = 0; i <= n; ++i) {
    const double s = static_cast<double>(i) / n;
    out.push_back(torus_point(u0 + s * (u1 - u0), v0 + s * (v1 - v0)));
  }
  return out;
}

/// Its skeleton: the upper saddle's two outgoing separatrices run round the
/// hole (the inner circle's two halves) into the lower saddle: two
/// saddle-to-saddle connections, separation lines as found from their first
/// saddle; the lower saddle's outgoing ones run over and under the tube to
/// the minimum (separation), the upper one's incoming ones come from the
/// maximum (attachment); and the outer circle, which the flow runs along
/// from the maximum to the minimum, spreads its neighbours on its upper
/// half (an attachment line) and gathers them on its lower half (a
/// separation line).
inline Truth torus_height_truth() {
  Truth t;
  t.points = {{torus_point(0, 0), CriticalKind::RepellingNode},
              {torus_point(0, kPi), CriticalKind::Saddle},
              {torus_point(kPi, kPi), CriticalKind::Saddle},
              {torus_point(kPi, 0), CriticalKind::AttractingNode}};
  t.lines = {
      {LineKind::Separation, torus_curve(0, kPi, kPi, kPi), "the inner circle, one half"},
      {LineKind::Separation, torus_curve(0, -kPi, kPi, kPi), "the inner circle, the other half"},
      {LineKind::Separation, torus_curve(kPi, kPi, kPi, 2 * kPi), "lower saddle to minimum, over"},
      {LineKind::Separation, torus_curve(kPi, kPi, kPi, 0), "lower saddle to minimum, under"},
      {LineKind::Attachment, torus_curve(0, 0, 0, kPi), "maximum to upper saddle, over"},
      {LineKind::Attachment, torus_curve(0, 0, 2 * kPi, kPi), "maximum to upper saddle, under"},
      {LineKind::Attachment, torus_curve(0, 0.5 * kPi, 0, 0), "outer circle, upper half, one side"},
      {LineKind::Attachment, torus_curve(0, -0.5 * kPi, 0, 0),
       "outer circle, upper half, other side"},
      {LineKind::Separation, torus_curve(0.5 * kPi, kPi, 0, 0),
       "outer circle, lower half, one side"},
      {LineKind::Separation, torus_curve(-0.5 * kPi, -kPi, 0, 0),
       "outer circle, lower half, other side"},
  };
  return t;
}

// ---- the measures

inline double distance_to(const glm::dvec3& p, const std::vector<glm::dvec3>& curve) {
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
    const glm::dvec3 a = curve[i], d = curve[i + 1] - a;
    const double l2 = glm::dot(d, d);
    const double t = l2 > 0.0 ? std::clamp(glm::dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
    best = std::min(best, glm::length(p - (a + t * d)));
  }
  return best;
}

inline double curve_length(const std::vector<glm::dvec3>& c) {
  double s = 0.0;
  for (std::size_t i = 1; i < c.size(); ++i) s += glm::length(c[i] - c[i - 1]);
  return s;
}

/// A found line's points, densely (every 0.002 along it), and its kind.
struct Dense {
  LineKind kind;
  std::vector<glm::dvec3> points;
  double length;
};
inline std::vector<Dense> densely(const FeatureLines& lines) {
  std::vector<Dense> out;
  for (const FeatureLine& l : lines.lines) {
    Dense d{l.kind, {}, 0.0};
    const std::size_t n = l.points.size();
    for (std::size_t i = 0; i + 1 < n + (l.closed ? 1 : 0); ++i) {
      const glm::dvec3 a(l.points[i].position), b(l.points[(i + 1) % n].position);
      const double len = glm::length(b - a);
      d.length += len;
      const int steps = std::max(1, static_cast<int>(std::ceil(len / 0.002)));
      for (int k = 0; k < steps; ++k)
        d.points.push_back(a + (b - a) * (static_cast<double>(k) / steps));
    }
    if (n) d.points.push_back(glm::dvec3(l.points.back().position));
    out.push_back(std::move(d));
  }
  return out;
}

struct LineScore {
  std::string what;
  double mean_distance = 1e300;  ///< of the found points of its kind nearest to it
  double covered = 0.0;          ///< fraction of its length within 0.02 of a found line of its kind
};

struct Score {
  std::vector<LineScore> lines;
  double elsewhere = 0.0;  ///< length of found lines (either kind) not on a true line of their kind
  double true_length = 0.0;
  std::vector<std::string> point_problems;
  std::string describe() const {
    std::string s;
    for (const LineScore& l : lines)
      s += l.what + ": mean distance " + std::to_string(l.mean_distance) + ", covered " +
           std::to_string(l.covered) + "\n";
    s += "elsewhere " + std::to_string(elsewhere) + " of " + std::to_string(true_length) + "\n";
    for (const std::string& p : point_problems) s += p + "\n";
    return s;
  }
};

/// The bounds, measured: a found point is a true one's when within
/// 0.03 and of its kind; a found line's point belongs to the true line of
/// its kind that is nearest, when within `near` (else it is elsewhere).
inline Score score(const FlowTopology& found, const Truth& truth, double near = 0.05) {
  Score s;
  std::vector<char> matched(found.critical.points.size(), 0);
  for (const TruePoint& tp : truth.points) {
    bool ok = false;
    for (std::size_t i = 0; i < found.critical.points.size(); ++i) {
      const CriticalPoint& p = found.critical.points[i];
      if (!matched[i] && p.kind == tp.kind && glm::length(glm::dvec3(p.position) - tp.at) <= 0.03) {
        matched[i] = 1;
        ok = true;
        break;
      }
    }
    if (!ok)
      s.point_problems.push_back(std::string("no ") + kind_name(tp.kind) +
                                 " found near the true one");
  }
  for (std::size_t i = 0; i < matched.size(); ++i)
    if (!matched[i])
      s.point_problems.push_back(std::string("a ") + kind_name(found.critical.points[i].kind) +
                                 " where there is none");
  const std::vector<Dense> dense = densely(found.lines);
  std::vector<double> sum(truth.lines.size(), 0.0);
  std::vector<std::size_t> count(truth.lines.size(), 0);
  for (const TrueLine& t : truth.lines) s.true_length += curve_length(t.points);
  for (const Dense& d : dense) {
    std::size_t away = 0;
    for (const glm::dvec3& p : d.points) {
      double best = near;
      std::size_t which = truth.lines.size();
      for (std::size_t k = 0; k < truth.lines.size(); ++k) {
        if (truth.lines[k].kind != d.kind) continue;
        const double dist = distance_to(p, truth.lines[k].points);
        if (dist < best) best = dist, which = k;
      }
      if (which == truth.lines.size()) {
        ++away;
        continue;
      }
      sum[which] += best;
      ++count[which];
    }
    if (!d.points.empty()) s.elsewhere += d.length * static_cast<double>(away) / d.points.size();
  }
  for (std::size_t k = 0; k < truth.lines.size(); ++k) {
    const TrueLine& t = truth.lines[k];
    LineScore ls{t.what, count[k] ? sum[k] / count[k] : 1e300, 0.0};
    std::size_t covered = 0, samples = 0;
    for (std::size_t i = 0; i < t.points.size(); i += 4, ++samples) {
      bool hit = false;
      for (const Dense& d : dense) {
        if (d.kind != t.kind) continue;
        for (const glm::dvec3& p : d.points)
          if (glm::length(p - t.points[i]) <= 0.02) {
            hit = true;
            break;
          }
        if (hit) break;
      }
      covered += hit;
    }
    ls.covered = samples ? static_cast<double>(covered) / samples : 0.0;
    s.lines.push_back(ls);
  }
  return s;
}

/// Whether a score meets the bounds.
inline bool within_bounds(const Score& s) {
  if (!s.point_problems.empty()) return false;
  for (const LineScore& l : s.lines)
    if (!(l.mean_distance <= 0.01) || !(l.covered >= 0.9)) return false;
  return s.elsewhere <= 0.05 * std::max(s.true_length, 1e-9);
}

}  // namespace ibfvs::exact
