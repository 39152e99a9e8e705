// Separation and attachment lines by following the field (topology.h):
// separatrices from the saddles, closed orbits by their first-return map,
// open lines from where the field's lines converge, and the lines of zeros
// (zero_lines.cpp); then the significance test and find_topology.
//
// Sections: scales and grids; LineFinder (tracing with its stops, closed
// orbits, separatrices, open lines); the critical points' simplification;
// find_topology.
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

namespace {

// ---- small geometry on the surface

// From p along the tangent direction `dir` for `dist`, across edges as a
// straight line unfolds (kept at the same angle to each edge it crosses).
SurfacePoint walk(const SurfaceField& f, SurfacePoint p, glm::dvec3 dir, double dist) {
  const TriMesh& mesh = f.mesh();
  for (int guard = 0; guard < 64 && dist > 1e-15; ++guard) {
    const TriangleFrame& fr = f.frame(p.triangle);
    glm::dvec3 d = dir - glm::dot(dir, fr.normal) * fr.normal;
    const double len = glm::length(d);
    if (!(len > 0.0)) return p;
    d /= len;
    const auto b0 = f.barycentric(p.triangle, p.position);
    const auto b1 = f.barycentric(p.triangle, p.position + dist * d);
    double leave = 2.0;
    int edge = -1;
    for (int i = 0; i < 3; ++i)
      if (b1[i] < 0.0) {
        const double tau = std::max(b0[i], 0.0) / (std::max(b0[i], 0.0) - b1[i]);
        if (tau < leave) leave = tau, edge = i;
      }
    if (edge < 0) {
      p.position += dist * d;
      return p;
    }
    p.position += leave * dist * d;
    dist -= leave * dist;
    const int k = (edge + 1) % 3;
    const std::uint32_t next = f.neighbour(p.triangle, k);
    if (next == kNoTriangle || !f.frame(next).valid) return p;
    // The same point in the next triangle's plane (on the shared edge).
    const Triangle& tri = mesh.triangles[p.triangle];
    const glm::dvec3 a(mesh.positions[tri[k]]), b(mesh.positions[tri[(k + 1) % 3]]);
    const double t = std::clamp(glm::dot(p.position - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
    p.position = a + t * (b - a);
    p.triangle = next;
    dir = d;
  }
  return p;
}

double polyline_length(const std::vector<TracePoint>& points, bool closed) {
  double len = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i)
    len += glm::length(points[i].position - points[i - 1].position);
  if (closed && points.size() > 1)
    len += glm::length(points.front().position - points.back().position);
  return len;
}

// A line's point in the grid of what has been found.
struct Mark {
  std::uint32_t line;
  glm::dvec3 position, to;  // a segment of the line
  glm::dvec3 flow;          // unit, along the flow; zero for a line of zeros
  [[nodiscard]] double distance(const glm::dvec3& p) const {
    const glm::dvec3 d = to - position;
    const double l2 = glm::dot(d, d);
    const double t = l2 > 0.0 ? std::clamp(glm::dot(p - position, d) / l2, 0.0, 1.0) : 0.0;
    return glm::length(p - (position + t * d));
  }
};

// ---- the finder

// The least convergence rate of a seed, per surface size: a line that
// converges at it all along a surface of size 1 gathers e^2 there. An open
// line ends where its rate over a scale falls below a quarter of it.
constexpr double kSeedRate = 2.0;

enum class Mode { Separatrix, Open, Extension };

// What ended a trace, beyond TraceEnd.
enum class Met { Nothing, Point, Line, Other, Cycle, Cut };

struct TraceResult {
  Trace trace;
  Met met = Met::Nothing;
  std::uint32_t point = 0;  // Met::Point: the critical point
  std::uint32_t line = 0;   // Met::Line: the line joined
  std::uint32_t section_from = 0, section_to = 0;
  std::size_t first_crossing = 0;  // Met::Cycle: the trace's index of its first crossing
  std::size_t truncate = 0;        // when not 0: the trace's points kept
};

class LineFinder {
 public:
  LineFinder(const SurfaceField& field, const Scales& scales, const TopologyOptions& options,
             const std::vector<CriticalPoint>& points)
      : f_(field),
        s_(scales),
        o_(options),
        points_(points),
        point_grid_(2.0 * scales.disk, field.lo(), field.hi()),
        saddle_grid_(scales.connect, field.lo(), field.hi()),
        merge_grid_(scales.merge + field.mean_edge(), field.lo(), field.hi()),
        line_grid_(scales.seed_gap + field.mean_edge(), field.lo(), field.hi()) {
    for (std::uint32_t i = 0; i < points_.size(); ++i) {
      point_grid_.insert(glm::dvec3(points_[i].position), i);
      if (points_[i].kind == CriticalKind::Saddle)
        saddle_grid_.insert(glm::dvec3(points_[i].position), i);
    }
  }

  void add(RawLine line) {
    const auto id = static_cast<std::uint32_t>(lines_.size());
    mark(line, id, 0);
    lines_.push_back(std::move(line));
  }

  void separatrices();
  void open_lines();
  void prune_open_lines();
  void join_ends();
  std::vector<RawLine> take() { return std::move(lines_); }

 private:
  // Marks the line's points from `from` on in the grid: a segment every
  // few points (a mark is the segment from its point to `to`), each in the
  // cells of its two ends.
  void mark(const RawLine& line, std::uint32_t id, std::size_t from) {
    constexpr std::size_t kEvery = 2;
    const bool zeros = line.origin == LineOrigin::Zeros;
    const std::size_t n = line.points.size();
    for (std::size_t i = from; i < n; i += kEvery) {
      const std::size_t j = std::min(i + kEvery, n - 1);
      const glm::dvec3 a = line.points[i].position, b = line.points[j].position;
      glm::dvec3 flow(0.0);
      if (!zeros && glm::length(b - a) > 0.0) flow = glm::normalize(b - a);
      if (!zeros && j == i && n > 1) {
        const glm::dvec3 d = a - line.points[n - 2].position;
        if (glm::length(d) > 0.0) flow = glm::normalize(d);
      }
      marks_.push_back({id, a, b, flow});
      const auto m = static_cast<std::uint32_t>(marks_.size() - 1);
      for (PointGrid* g : {&merge_grid_, &line_grid_}) {
        g->insert(a, m);
        if (g->key_of(a) != g->key_of(b)) g->insert(b, m);
      }
    }
  }

  // The kept critical point within the disk of p, if any (not `skip`).
  std::optional<std::uint32_t> point_near(const glm::dvec3& p,
                                          std::optional<std::uint32_t> skip) const {
    std::optional<std::uint32_t> best;
    double best_d = s_.disk;
    point_grid_.near(p, s_.disk, [&](std::uint32_t i) {
      if (skip && *skip == i) return;
      const double d = glm::length(glm::dvec3(points_[i].position) - p);
      if (d <= best_d) best_d = d, best = i;
    });
    return best;
  }

  // The kept saddle within `radius` of p, if any (not `skip`).
  std::optional<std::uint32_t> saddle_near(const glm::dvec3& p, double radius,
                                           std::optional<std::uint32_t> skip) const {
    std::optional<std::uint32_t> best;
    double best_d = radius;
    saddle_grid_.near(p, radius, [&](std::uint32_t i) {
      if (skip && *skip == i) return;
      const double d = glm::length(glm::dvec3(points_[i].position) - p);
      if (d <= best_d) best_d = d, best = i;
    });
    return best;
  }

  // Within the merge distance of p: the nearest line of `kind` whose flow
  // runs along `flow` (a line of zeros: any), and any of the other kind.
  struct Near {
    std::optional<std::uint32_t> same, other;
  };
  Near lines_near(const glm::dvec3& p, LineKind kind, const glm::dvec3& flow) const {
    Near out;
    double best = s_.merge;
    merge_grid_.near(p, s_.merge + f_.mean_edge(), [&](std::uint32_t m) {
      const Mark& mk = marks_[m];
      const double d = mk.distance(p);
      if (d > s_.merge) return;
      if (lines_[mk.line].kind != kind) {
        out.other = mk.line;
        return;
      }
      if (mk.flow != glm::dvec3(0.0) && flow != glm::dvec3(0.0) && glm::dot(mk.flow, flow) < 0.5)
        return;
      if (d <= best) best = d, out.same = mk.line;
    });
    return out;
  }

  // The line of `kind` within `radius` of p whose flow runs along `flow` (a
  // line of zeros: any), if any.
  std::optional<std::uint32_t> line_near(const glm::dvec3& p, LineKind kind, double radius,
                                         const glm::dvec3& flow) const {
    std::optional<std::uint32_t> best;
    double best_d = radius;
    line_grid_.near(p, radius + f_.mean_edge(), [&](std::uint32_t m) {
      const Mark& mk = marks_[m];
      if (lines_[mk.line].kind != kind) return;
      if (mk.flow != glm::dvec3(0.0) && flow != glm::dvec3(0.0) && glm::dot(mk.flow, flow) < 0.5)
        return;
      const double d = mk.distance(p);
      if (d <= best_d) best_d = d, best = mk.line;
    });
    return best;
  }

  TraceResult follow(const SurfacePoint& start, int sense, LineKind kind, Mode mode,
                     std::optional<std::uint32_t> origin) const;
  std::optional<RawLine> closed_orbit(const TraceResult& found, int sense);
  std::optional<std::pair<double, Trace>> first_return(std::uint32_t from, std::uint32_t to,
                                                       double lambda, int sense) const;
  double strength(const RawLine& line) const;
  RawLine to_line(const TraceResult& r, int sense, LineKind kind, LineOrigin origin) const;
  // Long enough, and (but for a separatrix: the skeleton of the flow, kept
  // whatever its strength while its saddle is) strong enough.
  bool significant(const RawLine& line) const {
    return line.points.size() >= 2 && polyline_length(line.points, line.closed) >= s_.min_length &&
           (line.origin == LineOrigin::Separatrix || line.strength >= o_.min_strength);
  }
  // Accepts an open line or separatrix found by a trace that joined
  // `joined` (or none): concatenated where it joined that line's end.
  void accept(RawLine line, const TraceResult& r, int sense);
  double distinct_strength(const RawLine& line, const RawLine& joined) const;

  const SurfaceField& f_;
  Scales s_;
  TopologyOptions o_;
  const std::vector<CriticalPoint>& points_;
  // Lines' marks: for a trace's merge (cells as wide as the merge distance
  // and a mark's length) and for the wider searches.
  PointGrid point_grid_, saddle_grid_, merge_grid_, line_grid_;
  std::vector<Mark> marks_;
  std::vector<RawLine> lines_;
  // Saddle-to-saddle connections found from their first saddle: (from, to).
  std::unordered_set<std::uint64_t> connections_;
};

// The convergence a segment adds to a line of `kind`: separation lines
// gather it where the field's lines converge (div < 0), attachment where
// they diverge.
double convergence(const SurfaceField& f, LineKind kind, std::uint32_t triangle, double length) {
  const double div = f.direction_divergence(triangle);
  return (kind == LineKind::Separation ? -div : div) * length;
}

TraceResult LineFinder::follow(const SurfacePoint& start, int sense, LineKind kind, Mode mode,
                               std::optional<std::uint32_t> origin) const {
  TraceResult r;
  // The cut of an open line: where its neighbours stop converging onto it
  // (its convergence falls this far below the most it reached).
  constexpr double kCut = 0.25;
  double conv = 0.0, best = 0.0;
  std::size_t best_at = 0;
  bool left_origin = !origin;
  std::unordered_map<std::uint64_t, std::size_t> crossings;
  std::size_t crossed = 0;
  struct Zone {
    std::uint32_t saddle;
    std::size_t entered, closest_at;
    double closest;
  };
  std::optional<Zone> zone;
  const auto visit = [&](const Trace& t) {
    const std::size_t i = t.points.size() - 1;
    const TracePoint& p = t.points[i];
    if (i == 0) return true;
    const TracePoint& q = t.points[i - 1];
    conv += convergence(f_, kind, p.triangle, p.arc - q.arc);
    if (origin && !left_origin &&
        glm::length(p.position - glm::dvec3(points_[*origin].position)) > 1.5 * s_.disk)
      left_origin = true;
    // A line found before: this one joins it (before it reaches the point
    // they may both run into).
    if (mode != Mode::Extension && left_origin) {
      const glm::dvec3 step = p.position - q.position;
      const double len = glm::length(step);
      if (len > 0.0) {
        const Near near = lines_near(p.position, kind, static_cast<double>(sense) * step / len);
        if (near.same) {
          r.met = Met::Line;
          r.line = *near.same;
          return false;
        }
        if (const auto l = near.other) {
          r.met = Met::Other;
          r.line = *l;
          return false;
        }
      }
    }
    // A kept critical point: the line ends there.
    if (left_origin || !origin) {
      if (const auto k = point_near(p.position, left_origin ? std::nullopt : origin)) {
        r.met = Met::Point;
        r.point = *k;
        return false;
      }
      // A line that passes a saddle within twice the scale and turns there
      // ran into it along its incoming separatrix and left along an
      // outgoing one: a connection at the scale, which the discrete field
      // (or any asymmetry) misses by a little.
      if (const auto k = saddle_near(p.position, s_.connect, left_origin ? std::nullopt : origin)) {
        const double d = glm::length(p.position - glm::dvec3(points_[*k].position));
        if (!zone || zone->saddle != *k) {
          zone = Zone{*k, i, i, d};
        } else if (d < zone->closest) {
          zone->closest = d;
          zone->closest_at = i;
        }
      } else if (zone) {
        // Left it: the turn from entering its zone to leaving.
        const auto dir = [&](std::size_t a, std::size_t b) {
          const glm::dvec3 v = t.points[b].position - t.points[a].position;
          const double len = glm::length(v);
          return len > 0.0 ? v / len : v;
        };
        const std::size_t e = zone->entered;
        const glm::dvec3 in = dir(e > 0 ? e - 1 : e, e > 0 ? e : e + 1), out = dir(i - 1, i);
        if (glm::dot(in, out) < std::cos(0.25 * 3.14159265358979)) {
          r.met = Met::Point;
          r.point = zone->saddle;
          r.truncate = zone->closest_at + 1;
          return false;
        }
        zone.reset();
      }
    }
    // Followed against its sense, a line that converges is unstable: an
    // error grows by the factor it converges by. The extension stops before
    // that is more than e^1.5; the part before comes from seeds there.
    if (mode == Mode::Extension && conv > 1.5) return false;
    if (mode != Mode::Separatrix) {
      if (conv > best) best = conv, best_at = i;
      if (conv < best - kCut) {
        r.met = Met::Cut;
        return false;
      }
    }
    // A crossing from q's triangle into p's, seen before close to where it
    // is now: the trace runs round a closed orbit (one seen far from it
    // was a turn of a spiral still on its way: the later one counts).
    // (Every crossing is looked up, every fourth kept: a closed orbit
    // crosses hundreds of edges a turn, its next turn some of the same.)
    if (q.triangle != p.triangle && i >= 2 && mode != Mode::Extension) {
      const std::uint64_t key = static_cast<std::uint64_t>(q.triangle) << 32 | p.triangle;
      auto it = crossings.find(key);
      if (it == crossings.end()) {
        if (++crossed % 4 == 0) crossings.emplace(key, i - 1);
      } else {
        const double gap = glm::length(t.points[it->second].position - q.position);
        if (gap <= 0.5 * f_.mean_edge()) {
          r.met = Met::Cycle;
          r.section_from = q.triangle;
          r.section_to = p.triangle;
          r.first_crossing = it->second;
          return false;
        }
        it->second = i - 1;
      }
    }
    return true;
  };
  r.trace = trace_line(f_, start, sense, s_.max_length, s_.step, visit);
  if (r.met == Met::Cut) r.trace.points.resize(best_at + 1);
  if (r.truncate) r.trace.points.resize(r.truncate);
  if (mode != Mode::Separatrix && (r.met == Met::Nothing || r.met == Met::Cut)) {
    // An open line ends where its neighbours stop converging onto it: its
    // trailing part over which the rate (over a scale's length) is weak is
    // no part of it.
    auto& pts = r.trace.points;
    std::vector<double> c(pts.size(), 0.0);
    for (std::size_t i = 1; i < pts.size(); ++i)
      c[i] = c[i - 1] + convergence(f_, kind, pts[i].triangle, pts[i].arc - pts[i - 1].arc);
    const double weak = 0.25 * kSeedRate / f_.size();
    std::size_t keep = pts.size();
    while (keep > 1) {
      const std::size_t i = keep - 1;
      std::size_t j = i;
      while (j > 0 && pts[i].arc - pts[j].arc < s_.fine) --j;
      if (pts[i].arc - pts[j].arc > 0.0 && (c[i] - c[j]) >= weak * (pts[i].arc - pts[j].arc)) break;
      --keep;
    }
    pts.resize(keep);
  }
  return r;
}

std::optional<std::pair<double, Trace>> LineFinder::first_return(std::uint32_t from,
                                                                 std::uint32_t to, double lambda,
                                                                 int sense) const {
  // The edge `from` shares with `to`, as a -> b.
  const TriMesh& mesh = f_.mesh();
  int k = -1;
  for (int e = 0; e < 3; ++e)
    if (f_.neighbour(from, e) == to) k = e;
  if (k < 0) return std::nullopt;
  const Triangle& tri = mesh.triangles[from];
  const glm::dvec3 a(mesh.positions[tri[k]]), b(mesh.positions[tri[(k + 1) % 3]]);
  std::optional<double> back;
  const auto visit = [&](const Trace& t) {
    const std::size_t i = t.points.size() - 1;
    if (i < 2) return true;
    if (t.points[i - 1].triangle == from && t.points[i].triangle == to) {
      const glm::dvec3 x = t.points[i - 1].position;
      back = glm::dot(x - a, b - a) / glm::dot(b - a, b - a);
      return false;
    }
    return true;
  };
  Trace t = trace_line(f_, {to, a + lambda * (b - a)}, sense, s_.max_length, s_.step, visit);
  if (!back) return std::nullopt;
  t.points.pop_back();  // the step after the crossing
  return std::make_pair(*back, std::move(t));
}

std::optional<RawLine> LineFinder::closed_orbit(const TraceResult& found, int sense) {
  // The first-return map P on the crossed edge: the trace gives two of its
  // values; the secant method finds its fixed point.
  const TriMesh& mesh = f_.mesh();
  int k = -1;
  for (int e = 0; e < 3; ++e)
    if (f_.neighbour(found.section_from, e) == found.section_to) k = e;
  if (k < 0) return std::nullopt;
  const Triangle& tri = mesh.triangles[found.section_from];
  const glm::dvec3 a(mesh.positions[tri[k]]), b(mesh.positions[tri[(k + 1) % 3]]);
  const auto param = [&](const glm::dvec3& x) {
    return glm::dot(x - a, b - a) / glm::dot(b - a, b - a);
  };
  const auto& pts = found.trace.points;
  double l0 = param(pts[found.first_crossing].position), l1 = param(pts[pts.size() - 2].position);
  double g0 = l1 - l0;
  auto r = first_return(found.section_from, found.section_to, l1, sense);
  if (!r) return std::nullopt;
  double g1 = r->first - l1;
  for (int iter = 0; iter < 16 && std::abs(g1) > 1e-10; ++iter) {
    const double denom = g1 - g0;
    if (std::abs(denom) < 1e-15 || std::abs(l1 - l0) < 1e-15) break;
    const double ln = std::clamp(l1 - g1 * (l1 - l0) / denom, 1e-9, 1.0 - 1e-9);
    auto rn = first_return(found.section_from, found.section_to, ln, sense);
    if (!rn) return std::nullopt;
    l0 = l1, g0 = g1;
    l1 = ln, g1 = rn->first - ln;
    r = std::move(rn);
  }
  if (std::abs(g1) > 1e-6) return std::nullopt;  // no closed orbit through this edge
  RawLine line;
  line.closed = true;
  line.origin = LineOrigin::ClosedOrbit;
  line.points = std::move(r->second.points);
  if (line.points.size() < 3) return std::nullopt;
  // Attracting in the trace's sense: its neighbours converge onto it.
  double c = 0.0;
  for (std::size_t i = 1; i < line.points.size(); ++i)
    c += convergence(f_, LineKind::Separation, line.points[i].triangle,
                     line.points[i].arc - line.points[i - 1].arc);
  line.kind = c >= 0.0 ? LineKind::Separation : LineKind::Attachment;
  line.strength = std::min(std::abs(c), kFullStrength);
  if (sense < 0) std::reverse(line.points.begin(), line.points.end());
  return line;
}

double LineFinder::strength(const RawLine& line) const {
  // Over the line less its ends within a kept critical point's disk: the
  // neighbours' convergence onto it, less the flow's own compression along
  // it (the ratio of its speeds), which an even contraction into a node
  // matches.
  const auto& p = line.points;
  if (p.size() < 2) return 0.0;
  // Near a critical point the field is its linear part, the same for
  // every line there: only what lies beyond twice its disk counts, and that
  // must be a line's length at least.
  // Nor what lies beside a line of zeros, where the directions flip.
  const auto near_point = [&](const glm::dvec3& x) {
    bool near = false;
    point_grid_.near(x, [&](std::uint32_t i) {
      if (glm::length(glm::dvec3(points_[i].position) - x) <= 2.0 * s_.disk) near = true;
    });
    if (!near && line.origin != LineOrigin::Zeros)
      line_grid_.near(x, 2.5 * f_.mean_edge(), [&](std::uint32_t m) {
        if (lines_[marks_[m].line].origin == LineOrigin::Zeros &&
            marks_[m].distance(x) <= 1.5 * f_.mean_edge())
          near = true;
      });
    return near;
  };
  std::size_t i0 = 0, i1 = p.size() - 1;
  while (i0 < i1 && near_point(p[i0].position)) ++i0;
  while (i1 > i0 && near_point(p[i1].position)) --i1;
  if (i1 <= i0) return 0.0;
  double measured = 0.0;
  for (std::size_t i = i0 + 1; i <= i1; ++i)
    measured += glm::length(p[i].position - p[i - 1].position);
  if (measured < s_.min_length) return 0.0;
  double c = 0.0;
  for (std::size_t i = i0 + 1; i <= i1; ++i)
    c += convergence(f_, line.kind, p[i].triangle, glm::length(p[i].position - p[i - 1].position));
  // A line that runs into a node or focus (out of one, for attachment): the
  // lines about it converge on the point, by the ratio of the distances to
  // it, whichever line one follows; that is no line's own.
  const std::optional<std::uint32_t> end =
      line.kind == LineKind::Separation ? line.to_point : line.from_point;
  if (end && points_[*end].kind != CriticalKind::Saddle) {
    const glm::dvec3 at(points_[*end].position);
    const bool forward = line.kind == LineKind::Separation;
    const double far = glm::length(p[forward ? i0 : i1].position - at);
    const double near = glm::length(p[forward ? i1 : i0].position - at);
    if (far > near && near > 0.0) c -= std::log(far / near);
  }
  const double s = c;
  return std::min(s, kFullStrength);
}

RawLine LineFinder::to_line(const TraceResult& r, int sense, LineKind kind,
                            LineOrigin origin) const {
  RawLine line;
  line.kind = kind;
  line.origin = origin;
  line.points = r.trace.points;
  if (r.met == Met::Point) {
    const CriticalPoint& cp = points_[r.point];
    line.points.push_back({glm::dvec3(cp.position), static_cast<std::uint32_t>(cp.triangle), 0.0});
    (sense > 0 ? line.to_point : line.from_point) = r.point;
  }
  if (sense < 0) std::reverse(line.points.begin(), line.points.end());
  return line;
}

void LineFinder::accept(RawLine line, const TraceResult& r, int sense) {
  line.strength = strength(line);
  if (r.met == Met::Line && r.line < lines_.size()) {
    RawLine& other = lines_[r.line];
    // Joined near the end of the other line that it runs into (its first
    // points along the trace's sense): the other line's start was traced
    // from a seed further on, and this trace from further upstream
    // continues it there. One line: this trace, then the other from where
    // it was joined.
    if (!other.closed && other.kind == line.kind && other.origin == LineOrigin::Open &&
        line.origin == LineOrigin::Open && !line.points.empty()) {
      std::vector<TracePoint> theirs = other.points, mine = line.points;
      if (sense < 0) {
        std::reverse(theirs.begin(), theirs.end());
        std::reverse(mine.begin(), mine.end());
      }
      const glm::dvec3 at = mine.back().position;
      std::size_t j = 0;
      double best = std::numeric_limits<double>::max();
      for (std::size_t k = 0; k < theirs.size(); ++k) {
        const double d = glm::length(theirs[k].position - at);
        if (d < best) best = d, j = k;
      }
      double from_start = 0.0;
      for (std::size_t k = 1; k <= j; ++k)
        from_start += glm::length(theirs[k].position - theirs[k - 1].position);
      // Within the other's extension (traced against its sense from its
      // seed: the less accurate part), from a seed as good (a ridge at
      // least half as steep), or a little past its start.
      const double reach = line.seed_rate >= 0.5 * other.seed_rate ? other.extension : 0.0;
      if (from_start <= reach + 2.0 * s_.fine) {
        mine.insert(mine.end(), theirs.begin() + static_cast<std::ptrdiff_t>(j) + 1, theirs.end());
        if (sense < 0) std::reverse(mine.begin(), mine.end());
        other.points = std::move(mine);
        other.strength = strength(other);
        other.extension = line.extension;
        other.seed_rate = line.seed_rate;
        RawLine added;
        added.kind = other.kind;
        added.origin = other.origin;
        added.points = line.points;
        mark(added, r.line, 0);
        return;
      }
    }
  }
  if (!significant(line)) return;
  if (r.met == Met::Line && r.line < lines_.size() && line.origin != LineOrigin::Separatrix &&
      distinct_strength(line, lines_[r.line]) < o_.min_strength)
    return;  // it only drew near the line it joined, as all its neighbours did
  add(std::move(line));
}

double LineFinder::distinct_strength(const RawLine& line, const RawLine& joined) const {
  // A line that runs into another converges onto it as its neighbours do:
  // what it gathers as a line of its own is its strength less the log of
  // how far it came in towards the other, from its first point to where it
  // joined (a neighbour just beside it came in as much).
  const auto distance = [&](const glm::dvec3& p) {
    double best = std::numeric_limits<double>::max();
    const std::size_t n = joined.points.size();
    for (std::size_t i = 0; i + 1 < n + (joined.closed ? 1 : 0); ++i) {
      const glm::dvec3 a = joined.points[i].position, d = joined.points[(i + 1) % n].position - a;
      const double l2 = glm::dot(d, d);
      const double t = l2 > 0.0 ? std::clamp(glm::dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
      best = std::min(best, glm::length(p - (a + t * d)));
    }
    return best;
  };
  // The line's far end from the junction: its first point along its sense.
  const bool forward = line.kind == LineKind::Separation;
  const glm::dvec3 far = forward ? line.points.front().position : line.points.back().position;
  const glm::dvec3 near = forward ? line.points.back().position : line.points.front().position;
  const double d0 = distance(far), d1 = std::max(distance(near), s_.merge);
  return line.strength - (d0 > d1 ? std::log(d0 / d1) : 0.0);
}

void LineFinder::separatrices() {
  // Every saddle's outgoing separatrices (the unstable manifold: separation
  // lines) first, then the incoming ones (attachment): a connection from one
  // saddle into another is found from the first, whichever saddle comes first.
  for (const int sense : {1, -1}) {
    for (std::uint32_t i = 0; i < points_.size(); ++i) {
      const CriticalPoint& p = points_[i];
      if (p.kind != CriticalKind::Saddle) continue;
      const auto t = static_cast<std::uint32_t>(p.triangle);
      const TriangleFrame& fr = f_.frame(t);
      const Eigen2 e = eigen2(f_.jacobian(t));
      if (!e.real) continue;
      const double kick = std::min(0.5 * s_.disk, 0.5 * std::sqrt(2.0 * fr.area));
      {
        const auto& v = e.vector[sense > 0 ? 1 : 0];
        const glm::dvec3 dir = fr.at(v[0], v[1]);
        const LineKind kind = sense > 0 ? LineKind::Separation : LineKind::Attachment;
        for (const double side : {1.0, -1.0}) {
          const SurfacePoint start = walk(f_, {t, glm::dvec3(p.position)}, side * dir, kick);
          TraceResult r = follow(start, sense, kind, Mode::Separatrix, i);
          if (r.met == Met::Cycle) {
            if (auto orbit = closed_orbit(r, sense)) {
              if (!line_near(orbit->points[orbit->points.size() / 2].position, orbit->kind,
                             s_.merge * 4.0, glm::dvec3(0.0)) &&
                  significant(*orbit))
                add(std::move(*orbit));
              r = follow(start, sense, kind, Mode::Separatrix, i);  // now it joins the orbit
            }
          }
          // An incoming separatrix that runs straight onto a connection into
          // this saddle is that connection, found from its first saddle.
          if (sense < 0 && r.met == Met::Other && r.line < lines_.size() &&
              lines_[r.line].origin == LineOrigin::Separatrix && lines_[r.line].to_point == i)
            continue;
          if (r.met == Met::Point && points_[r.point].kind == CriticalKind::Saddle) {
            const std::uint64_t from = sense > 0 ? i : r.point, to = sense > 0 ? r.point : i;
            const std::uint64_t key = from << 32 | to;
            if (sense < 0 && connections_.count(key)) continue;  // found from its first saddle
            if (sense > 0) connections_.insert(key);
          }
          RawLine line = to_line(r, sense, kind, LineOrigin::Separatrix);
          (sense > 0 ? line.from_point : line.to_point) = i;
          // The saddle is the line's first point (last, for an incoming one).
          const TracePoint at{glm::dvec3(p.position), t, 0.0};
          if (sense > 0)
            line.points.insert(line.points.begin(), at);
          else
            line.points.push_back(at);
          accept(std::move(line), r, sense);
        }
      }
    }
  }
}

void LineFinder::open_lines() {
  // Seeds: the ridges of the rate at which the field's lines converge (or
  // diverge): a point where, across the flow, they converge faster than a
  // little to either side, and fast; the fastest first. The rate is the
  // divergence of the directions (so no vertex's scale moves a seed),
  // area-weighted at the vertices and linear between them.
  const TriMesh& mesh = f_.mesh();
  const std::size_t n = mesh.positions.size();
  std::vector<double> vdiv(n, 0.0), weight(n, 0.0);
  for (std::uint32_t t = 0; t < f_.triangle_count(); ++t) {
    const TriangleFrame& fr = f_.frame(t);
    if (!fr.valid) continue;
    for (const std::uint32_t k : mesh.triangles[t]) {
      vdiv[k] += fr.area * f_.direction_divergence(t);
      weight[k] += fr.area;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (weight[i] > 0.0) vdiv[i] /= weight[i];
  const auto rate_at = [&](const SurfacePoint& p) {
    const auto b = f_.barycentric(p.triangle, p.position);
    const Triangle& tri = mesh.triangles[p.triangle];
    return b[0] * vdiv[tri[0]] + b[1] * vdiv[tri[1]] + b[2] * vdiv[tri[2]];
  };
  struct Seed {
    SurfacePoint at;
    LineKind kind;
    double rate;
  };
  // At least kSeedRate, and at least the median rate: on a real surface the
  // rate is large nearly everywhere (small features and noise), and only
  // where it stands out of that does a line draw traces onto itself.
  double threshold = kSeedRate / f_.size();
  {
    std::vector<double> rates;
    rates.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      if (weight[i] > 0.0) rates.push_back(std::abs(vdiv[i]));
    if (!rates.empty()) {
      auto mid = rates.begin() + static_cast<std::ptrdiff_t>(rates.size() / 2);
      std::nth_element(rates.begin(), mid, rates.end());
      threshold = std::max(threshold, *mid);
    }
  }
  const double side = 0.75 * f_.mean_edge();
  // The candidates: in each cell of a grid a scale wide, the few triangles
  // of each kind whose rate is the most (a ridge, where one runs through,
  // has the most across it); a busy real surface has tens of thousands of
  // small ridges, and a line draws every trace near it onto itself, so a
  // few seeds a scale along it are enough.
  constexpr std::size_t kPerCell = 2;
  std::vector<std::uint32_t> candidates;
  {
    const PointGrid cells(s_.fine);
    std::unordered_map<std::uint64_t, std::vector<std::pair<double, std::uint32_t>>> best;
    for (std::uint32_t t = 0; t < f_.triangle_count(); ++t) {
      if (!f_.frame(t).valid) continue;
      const Triangle& tri = mesh.triangles[t];
      const double rate = (vdiv[tri[0]] + vdiv[tri[1]] + vdiv[tri[2]]) / 3.0;
      if (std::abs(rate) < threshold) continue;
      const glm::dvec3 c =
          (glm::dvec3(mesh.positions[tri[0]]) + glm::dvec3(mesh.positions[tri[1]]) +
           glm::dvec3(mesh.positions[tri[2]])) /
          3.0;
      auto& top = best[cells.key_of(c) * 2 + (rate < 0.0 ? 0 : 1)];
      if (top.size() < kPerCell) {
        top.emplace_back(std::abs(rate), t);
      } else {
        auto low = std::min_element(top.begin(), top.end());
        if (std::abs(rate) > low->first) *low = {std::abs(rate), t};
      }
    }
    for (const auto& [key, top] : best)
      for (const auto& [rate, t] : top) candidates.push_back(t);
    std::sort(candidates.begin(), candidates.end());
  }
  // Each candidate's seed (if any), found in parallel.
  std::vector<std::optional<Seed>> found(candidates.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t ci = 0; ci < static_cast<std::int64_t>(candidates.size()); ++ci) {
    const std::uint32_t t = candidates[static_cast<std::size_t>(ci)];
    const auto ti = ci;
    const TriangleFrame& fr = f_.frame(t);
    if (!fr.valid) continue;
    const Triangle& tri = mesh.triangles[t];
    const glm::dvec3 centre =
        (glm::dvec3(mesh.positions[tri[0]]) + glm::dvec3(mesh.positions[tri[1]]) +
         glm::dvec3(mesh.positions[tri[2]])) /
        3.0;
    const SurfacePoint at{t, centre};
    const double here = rate_at(at);
    if (std::abs(here) < threshold) continue;
    const glm::dvec3 flow = f_.direction_at(at);
    const double lf = glm::length(flow);
    if (!(lf > 0.0)) continue;
    const glm::dvec3 across = glm::cross(fr.normal, flow / lf);
    // Not where a neighbouring triangle on either side across the flow
    // converges faster (diverges, for attachment): no ridge runs here.
    {
      bool faster_left = false, faster_right = false;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t o = f_.neighbour(t, k);
        if (o == kNoTriangle) continue;
        const Triangle& ot = mesh.triangles[o];
        const glm::dvec3 oc =
            (glm::dvec3(mesh.positions[ot[0]]) + glm::dvec3(mesh.positions[ot[1]]) +
             glm::dvec3(mesh.positions[ot[2]])) /
            3.0;
        const double side_of = glm::dot(oc - centre, across);
        const double other = rate_at({o, oc});
        const bool faster = here < 0.0 ? other < here : other > here;
        if (faster && side_of < 0.0) faster_left = true;
        if (faster && side_of > 0.0) faster_right = true;
      }
      if (faster_left && faster_right) continue;
    }
    // The rate at seven points across the flow, 3 spacings wide, and the
    // parabola that fits them best: its extreme is the ridge, where it lies
    // within this triangle's half-spacing (so that a ridge is seeded once).
    const double sgn = here < 0.0 ? 1.0 : -1.0;  // separation: the minimum of div
    double sx[5] = {0, 0, 0, 0, 0}, sy[3] = {0, 0, 0};
    for (int k = -3; k <= 3; ++k) {
      const double u = 0.5 * side * k;
      const double r =
          sgn * (k == 0 ? here : rate_at(walk(f_, at, u < 0 ? -across : across, std::abs(u))));
      double x = 1.0;
      for (int m = 0; m < 5; ++m, x *= u) {
        sx[m] += x;
        if (m < 3) sy[m] += x * r;
      }
    }
    // Normal equations of r = c0 + c1 u + c2 u^2 (Cramer's rule).
    const double m[3][3] = {{sx[0], sx[1], sx[2]}, {sx[1], sx[2], sx[3]}, {sx[2], sx[3], sx[4]}};
    const auto det3 = [](const double(&q)[3][3]) {
      return q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) -
             q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
             q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
    };
    const double d = det3(m);
    if (!(std::abs(d) > 0.0)) continue;
    double m1[3][3], m2[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        m1[r][c] = c == 1 ? sy[r] : m[r][c];
        m2[r][c] = c == 2 ? sy[r] : m[r][c];
      }
    const double c1 = det3(m1) / d, c2 = det3(m2) / d;
    // A ridge, and a marked one: across the seven points the rate falls
    // off its extreme by a tenth of it at least (a flat profile locates no
    // line).
    if (!(c2 * (1.5 * side) * (1.5 * side) >= 0.1 * std::abs(here))) continue;
    const double offset = -0.5 * c1 / c2;
    if (std::abs(offset) > 0.5 * side) continue;
    const SurfacePoint seed = walk(f_, at, offset < 0 ? -across : across, std::abs(offset));
    found[static_cast<std::size_t>(ti)] =
        Seed{seed, here < 0.0 ? LineKind::Separation : LineKind::Attachment, std::abs(here)};
  }
  // The strongest of each kind in each cell of a grid a scale wide: a
  // line draws every trace near it onto itself, so one seed a scale along
  // it is enough (a busy real surface has tens of thousands of ridges).
  std::vector<Seed> seeds;
  {
    std::unordered_map<std::uint64_t, std::size_t> best;
    const PointGrid cells(s_.fine);
    for (const std::optional<Seed>& seed : found) {
      if (!seed) continue;
      const std::uint64_t key =
          cells.key_of(seed->at.position) * 2 + (seed->kind == LineKind::Separation ? 0 : 1);
      const auto [it, fresh] = best.try_emplace(key, seeds.size());
      if (fresh)
        seeds.push_back(*seed);
      else if (seed->rate > seeds[it->second].rate)
        seeds[it->second] = *seed;
    }
  }
  std::sort(seeds.begin(), seeds.end(),
            [](const Seed& a, const Seed& b) { return a.rate > b.rate; });
  // Before them, where the field's lines run straight along the locus of
  // straight lines (their curvature n . (d x J d), J the directions'
  // Jacobian at the vertices, changes sign across it: the parallel-vectors
  // form of the eigenvector criterion, on the directions) and converge
  // fast: on a symmetric line these lie on it exactly.
  std::vector<glm::dmat3> jac(n, glm::dmat3(0.0));
  for (std::uint32_t t = 0; t < f_.triangle_count(); ++t) {
    const TriangleFrame& fr = f_.frame(t);
    if (!fr.valid) continue;
    const Triangle& tri = mesh.triangles[t];
    const auto& d = f_.corner_directions(t);
    const Mat2 j = triangle_jacobian(fr, glm::dvec3(mesh.positions[tri[1]]),
                                     glm::dvec3(mesh.positions[tri[2]]), d[0], d[1], d[2]);
    // In 3D: J3 = E J E^T, E = [e1 e2] (glm's outerProduct(c, r) is c r^T).
    const glm::dmat3 j3 =
        j.a * glm::outerProduct(fr.e1, fr.e1) + j.b * glm::outerProduct(fr.e1, fr.e2) +
        j.c * glm::outerProduct(fr.e2, fr.e1) + j.d * glm::outerProduct(fr.e2, fr.e2);
    for (const std::uint32_t k : tri) jac[k] += fr.area * j3;
  }
  std::vector<double> curvature(n, 0.0);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!(weight[i] > 0.0)) continue;
    const glm::dvec3& d = f_.direction(i);
    curvature[i] = glm::dot(f_.normal(i), glm::cross(d, (jac[i] / weight[i]) * d));
  }
  std::vector<Seed> straight;
  const double aligned = std::cos(30.0 * 3.14159265358979 / 180.0);
  for (std::uint32_t t = 0; t < f_.triangle_count(); ++t) {
    if (!f_.frame(t).valid) continue;
    const double div = f_.direction_divergence(t);
    if (std::abs(div) < threshold) continue;
    const Triangle& tri = mesh.triangles[t];
    glm::dvec3 ends[3];
    int crossings = 0;
    for (int k = 0; k < 3; ++k) {
      const double ca = curvature[tri[k]], cb = curvature[tri[(k + 1) % 3]];
      if ((ca > 0.0) == (cb > 0.0)) continue;
      const double u = ca / (ca - cb);
      ends[crossings++] = glm::dvec3(mesh.positions[tri[k]]) +
                          u * glm::dvec3(mesh.positions[tri[(k + 1) % 3]] - mesh.positions[tri[k]]);
    }
    if (crossings != 2) continue;
    const glm::dvec3 mid = 0.5 * (ends[0] + ends[1]), along = ends[1] - ends[0];
    const glm::dvec3 flow = f_.direction_at({t, mid});
    const double la = glm::length(along), lf = glm::length(flow);
    if (!(la > 0.0) || !(lf > 0.0) || std::abs(glm::dot(along, flow)) < aligned * la * lf) continue;
    straight.push_back(
        {{t, mid}, div < 0.0 ? LineKind::Separation : LineKind::Attachment, std::abs(div)});
  }
  std::sort(straight.begin(), straight.end(),
            [](const Seed& a, const Seed& b) { return a.rate > b.rate; });
  seeds.insert(seeds.begin(), straight.begin(), straight.end());
  PointGrid tried(s_.seed_gap, f_.lo(), f_.hi());
  std::vector<glm::dvec3> tried_at;
  for (const Seed& seed : seeds) {
    if (line_near(seed.at.position, LineKind::Separation, s_.seed_gap, glm::dvec3(0.0)) ||
        line_near(seed.at.position, LineKind::Attachment, s_.seed_gap, glm::dvec3(0.0)))
      continue;
    bool near_tried = false;
    tried.near(seed.at.position, s_.merge, [&](std::uint32_t k) {
      if (glm::length(tried_at[k] - seed.at.position) <= s_.merge) near_tried = true;
    });
    if (near_tried) continue;
    const int sense = seed.kind == LineKind::Separation ? 1 : -1;
    TraceResult ahead = follow(seed.at, sense, seed.kind, Mode::Open, std::nullopt);
    if (ahead.met == Met::Cycle) {
      if (auto orbit = closed_orbit(ahead, sense)) {
        if (!line_near(orbit->points[orbit->points.size() / 2].position, orbit->kind,
                       4.0 * s_.merge, glm::dvec3(0.0)) &&
            significant(*orbit))
          add(std::move(*orbit));
        continue;
      }
    }
    // The extension adds at most e^1.5 (follow's cap): a line too weak
    // ahead of its seed stays too weak (unless it joins another).
    if (ahead.met != Met::Line &&
        strength(to_line(ahead, sense, seed.kind, LineOrigin::Open)) < o_.min_strength - 1.5) {
      for (const TracePoint& p : ahead.trace.points) {
        tried.insert(p.position, static_cast<std::uint32_t>(tried_at.size()));
        tried_at.push_back(p.position);
      }
      continue;
    }
    const TraceResult behind = follow(seed.at, -sense, seed.kind, Mode::Extension, std::nullopt);
    // The line: behind (reversed) then ahead, in the trace's sense.
    TraceResult whole = ahead;
    std::vector<TracePoint> pts(behind.trace.points.rbegin(), behind.trace.points.rend());
    if (!pts.empty()) pts.pop_back();  // the seed, again
    pts.insert(pts.end(), ahead.trace.points.begin(), ahead.trace.points.end());
    whole.trace.points = std::move(pts);
    RawLine line = to_line(whole, sense, seed.kind, LineOrigin::Open);
    line.extension = behind.trace.points.empty() ? 0.0 : behind.trace.points.back().arc;
    line.seed_rate = seed.rate;
    if (behind.met == Met::Point) {  // it came from a critical point
      const CriticalPoint& cp = points_[behind.point];
      const TracePoint at{glm::dvec3(cp.position), static_cast<std::uint32_t>(cp.triangle), 0.0};
      if (sense > 0)
        line.points.insert(line.points.begin(), at);
      else
        line.points.push_back(at);
    }
    for (const TracePoint& p : line.points) {
      tried.insert(p.position, static_cast<std::uint32_t>(tried_at.size()));
      tried_at.push_back(p.position);
    }
    accept(std::move(line), ahead, sense);
  }
}

void LineFinder::prune_open_lines() {
  // An open line that runs into another line (or the point another runs
  // into) draws near it as its neighbours do; what it gathers as a line of
  // its own (distinct_strength) must be significant. And one that runs
  // beside a stronger line of its kind for most of its length is that
  // line's shadow. The weakest are judged first; a line dropped is no
  // longer one that others run into.
  std::vector<std::uint32_t> order;
  for (std::uint32_t i = 0; i < lines_.size(); ++i)
    if (lines_[i].origin == LineOrigin::Open) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return lines_[a].strength < lines_[b].strength;
  });
  std::vector<char> dropped(lines_.size(), 0);
  const double beside_radius = std::max(s_.seed_gap, 0.5 * s_.scale);
  // The line grid's cells are narrower than these searches.
  PointGrid wide(std::max(2.0 * s_.disk, beside_radius) + f_.mean_edge(), f_.lo(), f_.hi());
  for (std::uint32_t m = 0; m < marks_.size(); ++m) {
    wide.insert(marks_[m].position, m);
    if (wide.key_of(marks_[m].position) != wide.key_of(marks_[m].to)) wide.insert(marks_[m].to, m);
  }
  const auto nearest = [&](const glm::dvec3& p, std::uint32_t self, double radius) {
    std::optional<std::uint32_t> best;
    double best_d = radius;
    wide.near(p, radius + f_.mean_edge(), [&](std::uint32_t m) {
      const Mark& mk = marks_[m];
      if (mk.line == self || dropped[mk.line]) return;
      const double d = mk.distance(p);
      if (d <= best_d) best_d = d, best = mk.line;
    });
    return best;
  };
  for (const std::uint32_t i : order) {
    const RawLine& a = lines_[i];
    // Its end along its sense: where it runs into something.
    const bool forward = a.kind == LineKind::Separation;
    const glm::dvec3 end = forward ? a.points.back().position : a.points.front().position;
    bool drop = false;
    // (One that runs into a node or focus: its strength has the radial
    // convergence onto the point taken out already.)
    const bool at_point = forward ? a.to_point.has_value() : a.from_point.has_value();
    if (const auto b = nearest(end, i, 2.0 * s_.disk); b && !at_point)
      drop = distinct_strength(a, lines_[*b]) < o_.min_strength;
    if (!drop) {
      // (Every fourth point: they lie a quarter of an edge apart.)
      std::size_t beside = 0, seen = 0;
      for (std::size_t k = 0; k < a.points.size(); k += 4, ++seen) {
        const TracePoint& p = a.points[k];
        bool near = false;
        wide.near(p.position, beside_radius + f_.mean_edge(), [&](std::uint32_t m) {
          const Mark& mk = marks_[m];
          if (mk.line == i || dropped[mk.line]) return;
          const RawLine& b = lines_[mk.line];
          // Beside a line of the skeleton of either kind (within the
          // finder's resolution), or a stronger open one of its own kind
          // closer than half the significance scale: one feature.
          const double d = mk.distance(p.position);
          if (b.origin != LineOrigin::Open
                  ? d <= s_.seed_gap
                  : b.kind == a.kind && b.strength >= a.strength && d <= beside_radius)
            near = true;
        });
        beside += near;
      }
      drop = 2 * beside > seen;
    }
    dropped[i] = drop;
  }
  std::vector<RawLine> kept;
  for (std::uint32_t i = 0; i < lines_.size(); ++i)
    if (!dropped[i]) kept.push_back(std::move(lines_[i]));
  lines_ = std::move(kept);
}

void LineFinder::join_ends() {
  // A line of zeros whose chain breaks where the field's part along it
  // outweighs its part across (a 3-D solver's round-off) goes on there as a
  // traced line: lines of a kind that are neither separatrices nor closed,
  // whose ends meet (within twice the merge distance, each running on into
  // the other), are one line. The closest ends first.
  const double reach = 2.0 * s_.merge + 1e-12;
  const auto joinable = [&](const RawLine& l) {
    return !l.closed && l.points.size() >= 2 &&
           (l.origin == LineOrigin::Zeros || l.origin == LineOrigin::Open);
  };
  for (bool joined = true; joined;) {
    joined = false;
    double best = reach;
    std::size_t bi = 0, bj = 0;
    int how = -1;  // 0: i's back to j's front, 1: back-back, 2: front-front, 3: i closes
    for (std::size_t i = 0; i < lines_.size(); ++i) {
      if (!joinable(lines_[i])) continue;
      const glm::dvec3 ib = lines_[i].points.back().position,
                       ifr = lines_[i].points.front().position;
      if (lines_[i].points.size() > 3 && glm::length(ib - ifr) < best &&
          polyline_length(lines_[i].points, false) > 4.0 * reach)
        best = glm::length(ib - ifr), bi = i, how = 3;
      for (std::size_t j = i + 1; j < lines_.size(); ++j) {
        if (!joinable(lines_[j]) || lines_[j].kind != lines_[i].kind) continue;
        // Traced lines keep the flow's order: only back to front. Lines of
        // zeros have none: any ends.
        const bool free =
            lines_[i].origin == LineOrigin::Zeros || lines_[j].origin == LineOrigin::Zeros;
        const glm::dvec3 jb = lines_[j].points.back().position,
                         jf = lines_[j].points.front().position;
        const double d[4] = {glm::length(ib - jf), free ? glm::length(ib - jb) : 1e300,
                             free ? glm::length(ifr - jf) : 1e300, glm::length(jb - ifr)};
        for (int k = 0; k < 4; ++k)
          if (d[k] < best) best = d[k], bi = i, bj = j, how = k == 3 ? 4 : k;
      }
    }
    if (how < 0) break;
    joined = true;
    if (how == 3) {
      lines_[bi].closed = true;
      continue;
    }
    if (how == 4) {  // j's back to i's front: j then i
      std::swap(bi, bj);
      how = 0;
    }
    RawLine& a = lines_[bi];
    RawLine b = lines_[bj];
    if (how == 1) std::reverse(b.points.begin(), b.points.end());
    if (how == 2) std::reverse(a.points.begin(), a.points.end());
    a.points.insert(a.points.end(), b.points.begin(), b.points.end());
    if (b.origin == LineOrigin::Zeros) a.origin = LineOrigin::Zeros;
    a.strength = a.origin == LineOrigin::Zeros ? kFullStrength : std::max(a.strength, b.strength);
    lines_.erase(lines_.begin() + static_cast<std::ptrdiff_t>(bj));
  }
}

}  // namespace

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
    detail::LineFinder finder(field, s, options, t.critical.points);
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
