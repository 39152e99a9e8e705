// The topology between two steps of a series (topology_morph.h).
#include "ibfvs/core/fields/topology_morph.h"

#include <algorithm>
#include <cstddef>
#include <map>

#include <glm/geometric.hpp>

namespace ibfvs {
namespace {

std::vector<glm::vec3> positions(const FeatureLine& line) {
  std::vector<glm::vec3> out;
  out.reserve(line.points.size());
  for (const LinePoint& p : line.points) out.push_back(p.position);
  return out;
}

std::vector<glm::vec3> normals(const FeatureLine& line) {
  std::vector<glm::vec3> out;
  out.reserve(line.points.size());
  for (const LinePoint& p : line.points) out.push_back(p.normal);
  return out;
}

// The offset halfway from the chord a-b to the surface whose normals at a
// and b are na and nb: the sagitta of the arc with those normals, along
// their mean.
glm::vec3 bulge(const glm::vec3& a, const glm::vec3& na, const glm::vec3& b, const glm::vec3& nb) {
  const glm::vec3 mean = na + nb;
  const float len = glm::length(mean);
  if (!(len > 1e-6f)) return glm::vec3(0.0f);
  return (glm::dot(b - a, nb - na) / 8.0f) * (mean / len);
}

// `n` points at equal fractions of the polyline's length (a closed one
// returns to its start: the last point is not repeated).
std::vector<glm::vec3> resample(const std::vector<glm::vec3>& p, bool closed, std::size_t n) {
  std::vector<glm::vec3> path = p;
  if (closed && !p.empty()) path.push_back(p.front());
  std::vector<double> at(path.size(), 0.0);
  for (std::size_t i = 1; i < path.size(); ++i)
    at[i] = at[i - 1] + glm::length(glm::dvec3(path[i] - path[i - 1]));
  const double total = at.empty() ? 0.0 : at.back();
  std::vector<glm::vec3> out;
  out.reserve(n);
  std::size_t seg = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double denominator = closed ? static_cast<double>(n) : static_cast<double>(n - 1);
    const double s = n > 1 ? total * static_cast<double>(k) / denominator : 0.0;
    while (seg + 2 < path.size() && at[seg + 1] < s) ++seg;
    if (path.size() < 2) {
      out.push_back(path.empty() ? glm::vec3(0.0f) : path[0]);
      continue;
    }
    const double len = at[seg + 1] - at[seg];
    const float t =
        len > 0.0 ? static_cast<float>(std::clamp((s - at[seg]) / len, 0.0, 1.0)) : 0.0f;
    out.push_back(path[seg] + t * (path[seg + 1] - path[seg]));
  }
  return out;
}

float squared(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 d = a - b;
  return glm::dot(d, d);
}

// The two lines' points paired: both resampled to the longer one's count,
// the second turned to run as the first and, when closed, started at the
// point nearest the first's start.
void pair_lines(const FeatureLine& a, const FeatureLine& b, FeatureMorph& m) {
  const std::size_t n = std::max<std::size_t>({a.points.size(), b.points.size(), 2});
  std::vector<glm::vec3> pb = positions(b), nb = normals(b);
  std::vector<glm::vec3> na = resample(normals(a), a.closed, n);
  // The points' bulges, once the two ends are paired.
  const auto finish = [&](const std::vector<glm::vec3>& to_normals) {
    m.bulge.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      m.bulge[i] = bulge(m.from[i], glm::normalize(na[i]), m.to[i], glm::normalize(to_normals[i]));
  };
  if (b.closed) {
    // Start where the first starts, and run the way it runs.
    std::size_t best = 0;
    for (std::size_t i = 1; i < pb.size(); ++i)
      if (squared(pb[i], a.points.front().position) < squared(pb[best], a.points.front().position))
        best = i;
    const auto start = static_cast<std::ptrdiff_t>(best);
    std::rotate(pb.begin(), pb.begin() + start, pb.end());
    std::rotate(nb.begin(), nb.begin() + start, nb.end());
    const std::vector<glm::vec3> ra = resample(positions(a), a.closed, n);
    const std::vector<glm::vec3> rb = resample(pb, true, n);
    // The same start, the other way round.
    std::vector<glm::vec3> back(pb.rbegin(), pb.rend()), back_n(nb.rbegin(), nb.rend());
    std::rotate(back.begin(), back.end() - 1, back.end());
    std::rotate(back_n.begin(), back_n.end() - 1, back_n.end());
    const std::vector<glm::vec3> rr = resample(back, true, n);
    float forward = 0.0f, reverse = 0.0f;
    for (std::size_t i = 0; i < n; ++i) {
      forward += squared(ra[i], rb[i]);
      reverse += squared(ra[i], rr[i]);
    }
    m.from = ra;
    m.to = reverse < forward ? rr : rb;
    finish(resample(reverse < forward ? back_n : nb, true, n));
    return;
  }
  const glm::vec3 a0 = a.points.front().position, a1 = a.points.back().position;
  if (squared(a0, pb.back()) + squared(a1, pb.front()) <
      squared(a0, pb.front()) + squared(a1, pb.back())) {
    std::reverse(pb.begin(), pb.end());
    std::reverse(nb.begin(), nb.end());
  }
  m.from = resample(positions(a), false, n);
  m.to = resample(pb, false, n);
  finish(resample(nb, false, n));
}

FeatureMorph point_morph(const CriticalPoint& p, MorphSpan span) {
  return {static_cast<int>(p.kind), p.id, true, false, span, {p.position}, {p.position},
          {glm::vec3(0.0f)}};
}

FeatureMorph line_morph(const FeatureLine& l, MorphSpan span) {
  FeatureMorph m{static_cast<int>(l.kind), l.id, false, l.closed, span, positions(l), {}, {}};
  m.to = m.from;
  m.bulge.assign(m.from.size(), glm::vec3(0.0f));
  return m;
}

}  // namespace

glm::vec3 FeatureMorph::at(std::size_t i, float mix) const {
  return from[i] + mix * (to[i] - from[i]) + (4.0f * mix * (1.0f - mix)) * bulge[i];
}

bool shown_at(MorphSpan span, float mix) {
  switch (span) {
    case MorphSpan::FirstHalf:
      return mix < 0.5f;
    case MorphSpan::SecondHalf:
      return mix >= 0.5f;
    case MorphSpan::Whole:
      break;
  }
  return true;
}

TopologyMorph hold(const FlowTopology& topology) {
  TopologyMorph m;
  for (const CriticalPoint& p : topology.critical.points)
    m.features.push_back(point_morph(p, MorphSpan::Whole));
  for (const FeatureLine& l : topology.lines.lines)
    m.features.push_back(line_morph(l, MorphSpan::Whole));
  m.first = topology;
  m.second = topology;
  return m;
}

TopologyMorph morph_steps(const FlowTopology& from, const FlowTopology& to) {
  TopologyMorph m;
  std::map<int, const CriticalPoint*> next_points;
  std::map<int, const FeatureLine*> next_lines;
  for (const CriticalPoint& p : to.critical.points)
    if (p.id >= 0) next_points[p.id] = &p;
  for (const FeatureLine& l : to.lines.lines)
    if (l.id >= 0) next_lines[l.id] = &l;
  std::vector<char> point_paired(to.critical.points.size(), 0);
  std::vector<char> line_paired(to.lines.lines.size(), 0);
  for (const CriticalPoint& p : from.critical.points) {
    const auto it = p.id >= 0 ? next_points.find(p.id) : next_points.end();
    if (it == next_points.end()) {
      m.features.push_back(point_morph(p, MorphSpan::FirstHalf));
      continue;
    }
    const CriticalPoint& q = *it->second;
    point_paired[static_cast<std::size_t>(&q - to.critical.points.data())] = 1;
    // Moving on; a new kind from halfway.
    FeatureMorph f = point_morph(p, MorphSpan::Whole);
    f.to = {q.position};
    f.bulge = {bulge(p.position, p.normal, q.position, q.normal)};
    if (q.kind != p.kind) {
      f.span = MorphSpan::FirstHalf;
      FeatureMorph g = f;
      g.kind = static_cast<int>(q.kind);
      g.span = MorphSpan::SecondHalf;
      m.features.push_back(f);
      m.features.push_back(g);
    } else {
      m.features.push_back(f);
    }
  }
  for (const FeatureLine& l : from.lines.lines) {
    const auto it = l.id >= 0 ? next_lines.find(l.id) : next_lines.end();
    // A line that persists keeps its kind (carry_ids); one that opens or
    // closes is redrawn halfway.
    if (it == next_lines.end() || it->second->kind != l.kind || it->second->closed != l.closed ||
        l.points.empty() || it->second->points.empty()) {
      m.features.push_back(line_morph(l, MorphSpan::FirstHalf));
      continue;
    }
    const FeatureLine& q = *it->second;
    line_paired[static_cast<std::size_t>(&q - to.lines.lines.data())] = 1;
    FeatureMorph f{static_cast<int>(l.kind), l.id, false, l.closed, MorphSpan::Whole, {}, {}, {}};
    pair_lines(l, q, f);
    m.features.push_back(std::move(f));
  }
  for (std::size_t j = 0; j < to.critical.points.size(); ++j)
    if (!point_paired[j])
      m.features.push_back(point_morph(to.critical.points[j], MorphSpan::SecondHalf));
  for (std::size_t j = 0; j < to.lines.lines.size(); ++j)
    if (!line_paired[j]) m.features.push_back(line_morph(to.lines.lines[j], MorphSpan::SecondHalf));
  m.first = from;
  m.second = to;
  return m;
}

FlowTopology topology_at(const TopologyMorph& morph, float mix) {
  const FlowTopology& step = mix < 0.5f ? morph.first : morph.second;
  FlowTopology out;
  out.critical.index_sum = step.critical.index_sum;
  out.critical.degenerate_triangles = step.critical.degenerate_triangles;
  out.critical.zero_triangles = step.critical.zero_triangles;
  out.critical.cancelled = step.critical.cancelled;
  out.critical.on_lines = step.critical.on_lines;
  out.lines.scale = step.lines.scale;
  out.lines.mean_edge = step.lines.mean_edge;
  for (const FeatureMorph& f : morph.features) {
    if (!shown_at(f.span, mix)) continue;
    if (f.point) {
      CriticalPoint p;
      p.kind = static_cast<CriticalKind>(f.kind);
      p.id = f.id;
      p.position = f.at(0, mix);
      out.critical.points.push_back(p);
      continue;
    }
    FeatureLine l;
    l.kind = static_cast<LineKind>(f.kind);
    l.id = f.id;
    l.closed = f.closed;
    for (std::size_t i = 0; i < f.from.size(); ++i) {
      LinePoint p;
      p.position = f.at(i, mix);
      l.points.push_back(p);
    }
    out.lines.lines.push_back(std::move(l));
  }
  return out;
}

}  // namespace ibfvs
