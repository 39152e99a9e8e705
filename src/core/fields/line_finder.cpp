// The line finder (line_finder.h): traces and their stops, closed orbits by
// their first-return map, separatrices, and the joining of line ends.
#include "line_finder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

namespace ibfvs::detail {

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
      // A zero that is no kept point (one of a pair closer than the scale,
      // which cancel): the line ends there too, rather than turn about it.
      if (left_origin && zero_near(p.position)) {
        r.met = Met::Zero;
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
  r.visited.reserve(r.trace.points.size());
  for (const TracePoint& p : r.trace.points) r.visited.push_back(p.position);
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
    // (Every zero of the field: the kept points and those that cancel.)
    bool near = zero_grid_.near(
        x, [&](std::uint32_t i) { return glm::length(zeros_[i] - x) <= 2.0 * s_.disk; });
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

}  // namespace ibfvs::detail
