// Feature ids across the steps of a series (topology.h, carry_ids).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "ibfvs/core/fields/topology.h"
#include "topology_detail.h"

namespace ibfvs {
namespace {

struct Match {
  double cost;
  std::size_t from, to;
};

// The greedy assignment by cost: each of `from` and `to` used once.
std::vector<int> assign(std::vector<Match> matches, std::size_t from_count, std::size_t to_count) {
  std::sort(matches.begin(), matches.end(),
            [](const Match& a, const Match& b) { return a.cost < b.cost; });
  std::vector<int> to_from(to_count, -1);
  std::vector<char> used(from_count, 0);
  for (const Match& m : matches) {
    if (used[m.from] || to_from[m.to] >= 0) continue;
    used[m.from] = 1;
    to_from[m.to] = static_cast<int>(m.from);
  }
  return to_from;
}

}  // namespace

void carry_ids(const FlowTopology& previous, FlowTopology& next, int& next_id, double reach) {
  // Points: by index, within reach; their own kind a little nearer.
  std::vector<Match> pm;
  for (std::size_t i = 0; i < previous.critical.points.size(); ++i)
    for (std::size_t j = 0; j < next.critical.points.size(); ++j) {
      const CriticalPoint &a = previous.critical.points[i], &b = next.critical.points[j];
      if (a.index != b.index) continue;
      const double d = glm::length(glm::dvec3(a.position - b.position));
      if (d > reach) continue;
      pm.push_back({d + (a.kind == b.kind ? 0.0 : 0.5 * reach), i, j});
    }
  const std::vector<int> pfrom =
      assign(std::move(pm), previous.critical.points.size(), next.critical.points.size());
  for (std::size_t j = 0; j < next.critical.points.size(); ++j)
    next.critical.points[j].id =
        pfrom[j] >= 0 ? previous.critical.points[static_cast<std::size_t>(pfrom[j])].id : next_id++;
  // Lines: of a kind, lying along each other. Each line's points (at most
  // 32, evenly along it) against the earlier lines' segments near them (in
  // a grid of cells twice the reach wide): for each earlier line, the mean
  // distance to it (capped at twice the reach) and how many lie within reach.
  const double cap = 2.0 * reach;
  // (The earlier lines as chords about a quarter of the reach long: their
  // points lie much closer together than that.)
  struct Segment {
    glm::dvec3 a, b;
    std::uint32_t line;
  };
  std::vector<Segment> segments;
  detail::PointGrid grid(cap);
  const auto add = [&](const glm::dvec3& a, const glm::dvec3& e, std::uint32_t line) {
    const auto id = static_cast<std::uint32_t>(segments.size());
    segments.push_back({a, e, line});
    grid.insert(a, id);
    if (grid.key_of(a) != grid.key_of(e)) grid.insert(e, id);
  };
  for (std::uint32_t i = 0; i < previous.lines.lines.size(); ++i) {
    const FeatureLine& l = previous.lines.lines[i];
    if (l.points.empty()) continue;
    std::vector<glm::dvec3> path;
    for (const LinePoint& p : l.points) path.emplace_back(p.position);
    if (l.closed && path.size() > 1) path.push_back(path.front());
    glm::dvec3 from = path.front();
    for (std::size_t k = 1; k < path.size(); ++k)
      if (glm::length(path[k] - from) >= 0.25 * reach || k + 1 == path.size()) {
        add(from, path[k], i);
        from = path[k];
      }
    if (path.size() == 1) add(from, from, i);
  }
  const auto segment_distance = [&](const Segment& g, const glm::dvec3& p) {
    const glm::dvec3 d = g.b - g.a;
    const double l2 = glm::dot(d, d);
    const double t = l2 > 0.0 ? std::clamp(glm::dot(p - g.a, d) / l2, 0.0, 1.0) : 0.0;
    return glm::length(p - (g.a + t * d));
  };
  std::vector<Match> lm;
  std::vector<double> nearest(previous.lines.lines.size(), cap);
  std::vector<std::uint32_t> touched;
  struct Tally {
    double sum = 0.0;  // of (distance - cap) over the samples near the line
    std::size_t within = 0;
    bool listed = false;
  };
  std::vector<Tally> tally(previous.lines.lines.size());
  std::vector<std::uint32_t> candidates;
  for (std::size_t j = 0; j < next.lines.lines.size(); ++j) {
    const FeatureLine& b = next.lines.lines[j];
    if (b.points.empty()) continue;
    const std::size_t stride = std::max<std::size_t>(1, b.points.size() / 32);
    std::size_t seen = 0;
    candidates.clear();
    for (std::size_t k = 0; k < b.points.size(); k += stride, ++seen) {
      const glm::dvec3 p(b.points[k].position);
      touched.clear();
      grid.near(p, cap, [&](std::uint32_t id) {
        const Segment& g = segments[id];
        if (previous.lines.lines[g.line].kind != b.kind) return;
        const double d = segment_distance(g, p);
        if (d >= cap) return;
        if (nearest[g.line] >= cap) touched.push_back(g.line);
        nearest[g.line] = std::min(nearest[g.line], d);
      });
      for (const std::uint32_t i : touched) {
        if (!tally[i].listed) {
          tally[i].listed = true;
          candidates.push_back(i);
        }
        // (Each sample far from a line adds the cap: below.)
        tally[i].sum += nearest[i] - cap;
        tally[i].within += nearest[i] <= reach;
        nearest[i] = cap;
      }
    }
    for (const std::uint32_t i : candidates) {
      if (2 * tally[i].within >= seen)
        lm.push_back({cap + tally[i].sum / static_cast<double>(seen), i, j});
      tally[i] = Tally{};
    }
  }
  const std::vector<int> lfrom =
      assign(std::move(lm), previous.lines.lines.size(), next.lines.lines.size());
  for (std::size_t j = 0; j < next.lines.lines.size(); ++j)
    next.lines.lines[j].id =
        lfrom[j] >= 0 ? previous.lines.lines[static_cast<std::size_t>(lfrom[j])].id : next_id++;
}

}  // namespace ibfvs
