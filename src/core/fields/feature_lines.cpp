// Separation and attachment lines by following the field (topology.h):
// separatrices from the saddles, closed orbits by their first-return map,
// open lines from where the field's lines converge, and the lines of zeros
// (zero_lines.cpp); then the significance test and find_topology.
//
// Sections: scales; the critical points' simplification; find_topology.
// The line finder is line_finder.h (line_finder.cpp, open_lines.cpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "ibfvs/core/support/error.h"
#include "line_finder.h"
#include "topology_detail.h"

namespace ibfvs {
namespace detail {

Scales scales_of(const SurfaceField& f, const TopologyOptions& o) {
  // The finder's own lengths follow the mesh (its edges) and a fixed
  // fraction of the surface's size, whatever the significance scale asked
  // for: that only says what is kept.
  constexpr double kResolution = 0.02;
  Scales s;
  const double size = f.size(), edge = f.mean_edge(), fine = kResolution * size;
  s.scale = o.scale * size;
  s.fine = fine;
  s.merge = std::max({0.5 * edge, 0.25 * fine, 1e-9 * size});
  s.seed_gap = std::max(0.5 * fine, s.merge);
  s.disk = std::max(0.5 * fine, edge);
  s.connect = std::max(2.0 * s.disk, 2.0 * fine);
  s.step = 0.5 * edge;
  s.max_length = 5.0 * size;
  s.min_length = o.min_length * s.scale;
  return s;
}

// ---- the critical points' simplification

std::vector<CriticalPoint> simplify_points(std::vector<CriticalPoint> points,
                                           const std::vector<RawLine>& zeros, const Scales& s,
                                           double edge, CriticalPoints& counts) {
  // On a line of zeros: part of it.
  PointGrid zero_grid(std::max(1.5 * edge, 1e-12));
  std::vector<glm::dvec3> zero_at;
  for (const RawLine& l : zeros)
    for (const TracePoint& p : l.points) {
      zero_grid.insert(p.position, static_cast<std::uint32_t>(zero_at.size()));
      zero_at.push_back(p.position);
    }
  std::vector<CriticalPoint> kept;
  for (const CriticalPoint& p : points) {
    bool on = false;
    zero_grid.near(glm::dvec3(p.position), [&](std::uint32_t k) {
      if (glm::length(zero_at[k] - glm::dvec3(p.position)) <= 1.5 * edge) on = true;
    });
    if (on)
      ++counts.on_lines;
    else
      kept.push_back(p);
  }
  // A saddle and a node, focus or centre closer than the scale cancel, the
  // closest pairs first.
  PointGrid grid(std::max(s.scale, 1e-12));
  for (std::uint32_t i = 0; i < kept.size(); ++i) grid.insert(glm::dvec3(kept[i].position), i);
  struct Pair {
    double d;
    std::uint32_t a, b;
  };
  std::vector<Pair> pairs;
  for (std::uint32_t i = 0; i < kept.size(); ++i) {
    if (kept[i].kind != CriticalKind::Saddle) continue;
    grid.near(glm::dvec3(kept[i].position), [&](std::uint32_t j) {
      if (kept[j].kind == CriticalKind::Saddle) return;
      const double d = glm::length(kept[i].position - kept[j].position);
      if (d < s.scale) pairs.push_back({d, i, j});
    });
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) { return x.d < y.d; });
  std::vector<char> gone(kept.size(), 0);
  for (const Pair& p : pairs) {
    if (gone[p.a] || gone[p.b]) continue;
    gone[p.a] = gone[p.b] = 1;
    counts.cancelled += 2;
  }
  std::vector<CriticalPoint> out;
  for (std::uint32_t i = 0; i < kept.size(); ++i)
    if (!gone[i]) out.push_back(kept[i]);
  return out;
}

}  // namespace detail

const char* kind_name(LineKind kind) {
  return kind == LineKind::Separation ? "separation line" : "attachment line";
}

const char* origin_name(LineOrigin origin) {
  switch (origin) {
    case LineOrigin::Separatrix:
      return "separatrix";
    case LineOrigin::ClosedOrbit:
      return "closed orbit";
    case LineOrigin::Open:
      return "open";
    case LineOrigin::Zeros:
      return "zeros";
  }
  return "unknown";
}

void check_topology_options(const TopologyOptions& o) {
  if (!std::isfinite(o.scale) || !(o.scale > 0.0) || o.scale > 1.0)
    throw InputError(
        "topology: the scale must be in (0, 1] (a fraction of the surface's size), got " +
        std::to_string(o.scale));
  if (!std::isfinite(o.min_strength) || o.min_strength < 0.0)
    throw InputError("topology: the least strength must be a number of at least 0, got " +
                     std::to_string(o.min_strength));
  if (!std::isfinite(o.min_length) || o.min_length < 0.0)
    throw InputError("topology: the least length must be a number of at least 0, got " +
                     std::to_string(o.min_length));
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
                           const TopologyOptions& options) {
  check_topology_options(options);
  const SurfaceField field(mesh, vectors);
  FlowTopology t;
  t.critical = find_critical_points(field);
  const detail::Scales s = detail::scales_of(field, options);
  t.lines.scale = s.scale;
  t.lines.mean_edge = field.mean_edge();
  if (field.triangle_count() == 0) return t;
  // Every zero of the field, kept or not: where a skin-friction line ends.
  std::vector<glm::dvec3> all_zeros;
  all_zeros.reserve(t.critical.points.size());
  for (const CriticalPoint& p : t.critical.points) all_zeros.emplace_back(p.position);
  std::vector<detail::RawLine> zeros = detail::find_zero_lines(field, s);
  t.critical.points = detail::simplify_points(std::move(t.critical.points), zeros, s,
                                              field.mean_edge(), t.critical);
  // The kept points' indices: a cancelled pair's sum to 0, and a line of
  // zeros, across which the flow only turns back, has index 0 as a whole
  // (its scattered zeros alternate saddle and node).
  t.critical.index_sum = 0;
  for (const CriticalPoint& p : t.critical.points) t.critical.index_sum += p.index;
  std::vector<detail::RawLine> raw;
  {
    detail::LineFinder finder(field, s, options, t.critical.points, all_zeros);
    for (detail::RawLine& z : zeros) finder.add(std::move(z));
    finder.separatrices();
    finder.open_lines();
    finder.prune_open_lines();
    finder.join_ends();
    raw = finder.take();
  }
  for (const detail::RawLine& r : raw) {
    FeatureLine line;
    line.kind = r.kind;
    line.origin = r.origin;
    line.closed = r.closed;
    line.strength = r.strength;
    line.length = detail::polyline_length(r.points, r.closed);
    for (const TracePoint& p : r.points) {
      LinePoint lp;
      lp.position = glm::vec3(p.position);
      const SurfacePoint at{p.triangle, p.position};
      lp.normal = glm::vec3(field.normal_at(at));
      lp.magnitude = static_cast<float>(glm::length(field.field_at(at)));
      const Eigen2 e = eigen2(field.jacobian(p.triangle));
      if (e.real) lp.eigen = e.value;
      line.points.push_back(lp);
    }
    t.lines.lines.push_back(std::move(line));
  }
  int id = 0;
  for (CriticalPoint& p : t.critical.points) p.id = id++;
  for (FeatureLine& l : t.lines.lines) l.id = id++;
  return t;
}

}  // namespace ibfvs
