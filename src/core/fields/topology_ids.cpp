// Feature ids across the steps of a series (topology.h, carry_ids).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>

#include "ibfvs/core/fields/topology.h"

namespace ibfvs {
namespace {

// The distance from p to the polyline `line`.
double distance_to(const glm::vec3& p, const FeatureLine& line) {
  double best = std::numeric_limits<double>::max();
  const std::size_t n = line.points.size();
  if (n == 1) return glm::length(glm::dvec3(p - line.points[0].position));
  for (std::size_t i = 0; i + 1 < n + (line.closed ? 1 : 0); ++i) {
    const glm::dvec3 a(line.points[i].position),
        d = glm::dvec3(line.points[(i + 1) % n].position) - a;
    const double l2 = glm::dot(d, d);
    const double t = l2 > 0.0 ? std::clamp(glm::dot(glm::dvec3(p) - a, d) / l2, 0.0, 1.0) : 0.0;
    best = std::min(best, glm::length(glm::dvec3(p) - (a + t * d)));
  }
  return best;
}

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
  // Lines: of a kind, lying along each other.
  std::vector<Match> lm;
  for (std::size_t i = 0; i < previous.lines.lines.size(); ++i)
    for (std::size_t j = 0; j < next.lines.lines.size(); ++j) {
      const FeatureLine &a = previous.lines.lines[i], &b = next.lines.lines[j];
      if (a.kind != b.kind || a.points.empty() || b.points.empty()) continue;
      double sum = 0.0;
      std::size_t within = 0;
      for (const LinePoint& p : b.points) {
        const double d = distance_to(p.position, a);
        sum += std::min(d, 4.0 * reach);
        within += d <= reach;
      }
      if (2 * within < b.points.size()) continue;
      lm.push_back({sum / static_cast<double>(b.points.size()), i, j});
    }
  const std::vector<int> lfrom =
      assign(std::move(lm), previous.lines.lines.size(), next.lines.lines.size());
  for (std::size_t j = 0; j < next.lines.lines.size(); ++j)
    next.lines.lines[j].id =
        lfrom[j] >= 0 ? previous.lines.lines[static_cast<std::size_t>(lfrom[j])].id : next_id++;
}

}  // namespace ibfvs
