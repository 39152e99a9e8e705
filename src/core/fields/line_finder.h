#pragma once
// The line finder of find_topology (topology.h, feature_lines.cpp): traces
// with their stops, separatrices and closed orbits (line_finder.cpp), open
// lines and their pruning (open_lines.cpp). Private to src/core/fields.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <unordered_set>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "topology_detail.h"

namespace ibfvs::detail {

// ---- small geometry on the surface

// From p along the tangent direction `dir` for `dist`, across edges as a
// straight line unfolds (kept at the same angle to each edge it crosses).
SurfacePoint walk(const SurfaceField& f, SurfacePoint p, glm::dvec3 dir, double dist);

inline double polyline_length(const std::vector<TracePoint>& points, bool closed) {
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
enum class Met { Nothing, Point, Line, Other, Cycle, Cut, Zero };

struct TraceResult {
  Trace trace;
  Met met = Met::Nothing;
  std::uint32_t point = 0;  // Met::Point: the critical point
  std::uint32_t line = 0;   // Met::Line: the line joined
  std::uint32_t section_from = 0, section_to = 0;
  std::size_t first_crossing = 0;   // Met::Cycle: the trace's index of its first crossing
  std::size_t truncate = 0;         // when not 0: the trace's points kept
  std::vector<glm::dvec3> visited;  // every point the trace looked at, the cut part too
};

class LineFinder {
 public:
  // `points`: the kept critical points; `zeros`: every zero of the field
  // (cancelled ones too), where a skin-friction line ends.
  LineFinder(const SurfaceField& field, const Scales& scales, const TopologyOptions& options,
             const std::vector<CriticalPoint>& points, const std::vector<glm::dvec3>& zeros)
      : f_(field),
        s_(scales),
        o_(options),
        points_(points),
        zeros_(zeros),
        zero_grid_(2.0 * scales.disk, field.lo(), field.hi()),
        point_grid_(2.0 * scales.disk, field.lo(), field.hi()),
        saddle_grid_(scales.connect, field.lo(), field.hi()),
        merge_grid_(scales.merge + field.mean_edge(), field.lo(), field.hi()),
        line_grid_(scales.seed_gap + field.mean_edge(), field.lo(), field.hi()) {
    for (std::uint32_t i = 0; i < zeros_.size(); ++i) zero_grid_.insert(zeros_[i], i);
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

  // Whether a zero of the field lies within the disk of p.
  bool zero_near(const glm::dvec3& p) const {
    return zero_grid_.near(p, s_.disk,
                           [&](std::uint32_t i) { return glm::length(zeros_[i] - p) <= s_.disk; });
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

  // Whether a mark from `first` on lies within the merge distance of a
  // point `r` visited: what follow() saw before those marks were made may
  // differ from what it would see now.
  bool sees_marks_from(const TraceResult& r, std::size_t first) const {
    for (const glm::dvec3& p : r.visited)
      if (merge_grid_.near(p, s_.merge + f_.mean_edge(), [&](std::uint32_t m) {
            return m >= first && marks_[m].distance(p) <= s_.merge;
          }))
        return true;
    return false;
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
  const std::vector<glm::dvec3>& zeros_;
  // The zeros, the points, and the lines' marks: for a trace's merge
  // (cells as wide as the merge distance and a mark's length) and for the
  // wider searches.
  PointGrid zero_grid_, point_grid_, saddle_grid_, merge_grid_, line_grid_;
  std::vector<Mark> marks_;
  std::vector<RawLine> lines_;
  // Saddle-to-saddle connections found from their first saddle: (from, to).
  std::unordered_set<std::uint64_t> connections_;
};

// The convergence a segment adds to a line of `kind`: separation lines
// gather it where the field's lines converge (div < 0), attachment where
// they diverge.
double convergence(const SurfaceField& f, LineKind kind, std::uint32_t triangle, double length);

}  // namespace ibfvs::detail
