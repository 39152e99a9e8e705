// Lines of zeros (topology.h): where the field vanishes along a curve, as the
// wall shear does along a 2-D or axisymmetric separation line, the flow on
// either side of it points the opposite way across it. An edge whose ends'
// directions are nearly opposite and point towards each other (away from
// each other) crosses a separation (attachment) line of zeros; the crossing
// is where the linear field's component across the line is zero. The
// crossings of a triangle's two such edges are joined, and the pieces
// chained through the edges they share.
#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "topology_detail.h"

namespace ibfvs::detail {
namespace {

// Two ends' directions at least this far apart (140 degrees) are "nearly
// opposite": a smooth field turns by a few degrees across an edge; at the
// mesh's scale an isolated zero turns it by at most 120 degrees over a
// triangle's three corners, so a whole triangle's worth of such edges
// only happens across a line.
const double kOpposite = std::cos(140.0 * 3.14159265358979 / 180.0);
// Each corner's direction has at least this part across the line: where the
// flow on either side runs along it in opposite senses (a reversal along
// the line, not across it), the field vanishes there too but nothing
// separates.
constexpr double kAcross = 0.2;

struct Crossing {
  glm::dvec3 position;
  std::uint32_t triangle;
};

std::optional<Crossing> edge_crossing(const SurfaceField& f, std::uint32_t a, std::uint32_t b,
                                      std::uint32_t triangle) {
  const glm::dvec3 &da = f.direction(a), &db = f.direction(b);
  if (da == glm::dvec3(0.0) || db == glm::dvec3(0.0)) return std::nullopt;
  if (glm::dot(da, db) > kOpposite) return std::nullopt;
  const glm::dvec3 pa(f.mesh().positions[a]), pb(f.mesh().positions[b]);
  // The cross-flow along the axis the two directions share: zero where the
  // linear field's part along it is.
  const glm::dvec3 axis = glm::normalize(da - db);
  const double fa = glm::dot(f.tangent(a), axis), fb = glm::dot(f.tangent(b), axis);
  if (!(fa > 0.0) || !(fb < 0.0)) return std::nullopt;
  const double t = fa / (fa - fb);
  return Crossing{pa + t * (pb - pa), triangle};
}

// The kind of the piece from c0 to c1 in triangle t: separation where every
// corner's flow heads for it, attachment where every one heads away.
std::optional<LineKind> piece_kind(const SurfaceField& f, std::uint32_t t, const glm::dvec3& c0,
                                   const glm::dvec3& c1) {
  const TriangleFrame& fr = f.frame(t);
  glm::dvec3 along = c1 - c0;
  const double len = glm::length(along);
  if (!(len > 0.0)) return std::nullopt;
  along /= len;
  const glm::dvec3 across = glm::cross(fr.normal, along);
  const glm::dvec3 mid = 0.5 * (c0 + c1);
  int in = 0, out = 0;
  const Triangle& tri = f.mesh().triangles[t];
  for (int k = 0; k < 3; ++k) {
    const double side = glm::dot(glm::dvec3(f.mesh().positions[tri[k]]) - mid, across);
    const double flow = glm::dot(f.corner_directions(t)[k], across);
    // Flow along the line, not across it: a reversal along it, no separation.
    if (std::abs(flow) < kAcross) return std::nullopt;
    if (side * flow < 0.0)
      ++in;
    else
      ++out;
  }
  if (in == 3) return LineKind::Separation;
  if (out == 3) return LineKind::Attachment;
  return std::nullopt;
}

}  // namespace

std::vector<RawLine> find_zero_lines(const SurfaceField& f, const Scales& scales) {
  const TriMesh& mesh = f.mesh();
  // Each edge's crossing, on its canonical half-edge (3 t + k of the
  // triangle t with the lower index), found once, in parallel.
  const std::size_t nt = f.triangle_count();
  const auto canonical = [&](std::uint32_t t, int k) -> std::uint64_t {
    const std::uint32_t o = f.neighbour(t, k);
    if (o == kNoTriangle || t < o)
      return 3 * static_cast<std::uint64_t>(t) + static_cast<std::uint64_t>(k);
    return 3 * static_cast<std::uint64_t>(o) + static_cast<std::uint64_t>(f.neighbour_edge(t, k));
  };
  std::vector<std::optional<Crossing>> crossings(3 * nt);
#pragma omp parallel for schedule(static)
  for (std::int64_t ti = 0; ti < static_cast<std::int64_t>(nt); ++ti) {
    const auto t = static_cast<std::uint32_t>(ti);
    if (!f.frame(t).valid) continue;
    const Triangle& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k)
      if (canonical(t, k) == 3 * static_cast<std::uint64_t>(t) + static_cast<std::uint64_t>(k))
        crossings[3 * t + k] = edge_crossing(f, tri[k], tri[(k + 1) % 3], t);
  }
  const auto crossing = [&](std::uint32_t t, int k) -> const Crossing* {
    const std::optional<Crossing>& c = crossings[canonical(t, k)];
    return c ? &*c : nullptr;
  };
  const auto position_of = [&](std::uint64_t key) { return crossings[key]->position; };
  const auto triangle_of = [&](std::uint64_t key) { return crossings[key]->triangle; };
  // A piece per triangle with two crossings of one kind.
  struct Piece {
    std::uint64_t end[2];
    LineKind kind;
  };
  std::vector<Piece> pieces;
  for (std::uint32_t t = 0; t < f.triangle_count(); ++t) {
    if (!f.frame(t).valid) continue;
    std::uint64_t keys[3];
    const Crossing* found[3];
    int n = 0;
    for (int k = 0; k < 3; ++k)
      if (const Crossing* c = crossing(t, k)) {
        keys[n] = canonical(t, k);
        found[n++] = c;
      }
    if (n != 2) continue;
    if (const auto kind = piece_kind(f, t, found[0]->position, found[1]->position))
      pieces.push_back({{keys[0], keys[1]}, *kind});
  }
  // Chains through the edges the pieces share.
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> at;
  for (std::uint32_t i = 0; i < pieces.size(); ++i)
    for (const std::uint64_t e : pieces[i].end) at[e].push_back(i);
  std::vector<char> used(pieces.size(), 0);
  const auto next = [&](std::uint32_t from, std::uint64_t edge) -> std::optional<std::uint32_t> {
    for (const std::uint32_t k : at[edge])
      if (k != from && !used[k] && pieces[k].kind == pieces[from].kind) return k;
    return std::nullopt;
  };
  std::vector<RawLine> chains;
  for (std::uint32_t start = 0; start < pieces.size(); ++start) {
    if (used[start]) continue;
    used[start] = 1;
    std::vector<std::uint64_t> back{pieces[start].end[0]}, on{pieces[start].end[1]};
    bool closed = false;
    for (int dir = 0; dir < 2 && !closed; ++dir) {
      std::vector<std::uint64_t>& path = dir == 0 ? on : back;
      std::uint32_t here = start;
      while (const auto k = next(here, path.back())) {
        used[*k] = 1;
        const Piece& g = pieces[*k];
        const std::uint64_t far = g.end[0] == path.back() ? g.end[1] : g.end[0];
        if (far == (dir == 0 ? back.front() : on.front())) {
          closed = true;
          break;
        }
        path.push_back(far);
        here = *k;
      }
    }
    RawLine line;
    line.kind = pieces[start].kind;
    line.origin = LineOrigin::Zeros;
    line.closed = closed;
    line.strength = kFullStrength;
    std::vector<std::uint64_t> keys(back.rbegin(), back.rend());
    keys.insert(keys.end(), on.begin(), on.end());
    double length = 0.0;
    for (const std::uint64_t key : keys) {
      const glm::dvec3 where = position_of(key);
      if (!line.points.empty()) length += glm::length(where - line.points.back().position);
      line.points.push_back({where, triangle_of(key), length});
    }
    if (line.points.size() >= 2) chains.push_back(std::move(line));
  }
  // Where a vertex beside the line flows along it (the field's part along
  // the line, which a 3-D solver's round-off makes, outweighs its part
  // across there), the chain breaks for a triangle or two: chains of a kind
  // whose ends are that close are one line. The closest ends first.
  const double gap = 4.0 * f.mean_edge();
  // An end's direction: from a point a little back along its chain.
  const auto tangent_at = [](const RawLine& l, bool back) {
    const std::size_t n = l.points.size(), k = std::min<std::size_t>(n - 1, 3);
    const glm::dvec3 d = back ? l.points[n - 1].position - l.points[n - 1 - k].position
                              : l.points[0].position - l.points[k].position;
    const double len = glm::length(d);
    return len > 0.0 ? d / len : d;
  };
  // Whether the gap from end a (heading out along ta) to end b (heading out
  // along tb) continues both: it runs on from a and into b.
  const auto continues = [](const glm::dvec3& a, const glm::dvec3& ta, const glm::dvec3& b,
                            const glm::dvec3& tb) {
    const glm::dvec3 g = b - a;
    const double len = glm::length(g);
    if (!(len > 0.0)) return true;
    return glm::dot(g / len, ta) > 0.7 && glm::dot(-g / len, tb) > 0.7;
  };
  // The ends (2 c: chain c's front, 2 c + 1 its back), linked greedily,
  // the closest first, each end once: the chains then form paths and loops.
  const std::size_t ends = 2 * chains.size();
  const auto end_at = [&](std::size_t e) {
    const RawLine& l = chains[e / 2];
    return e % 2 ? l.points.back().position : l.points.front().position;
  };
  PointGrid grid(gap, f.lo(), f.hi());
  for (std::size_t e = 0; e < ends; ++e) grid.insert(end_at(e), static_cast<std::uint32_t>(e));
  struct Link {
    double d;
    std::size_t a, b;
  };
  std::vector<Link> links;
  for (std::size_t e = 0; e < ends; ++e) {
    const RawLine& l = chains[e / 2];
    const glm::dvec3 pe = end_at(e), te = tangent_at(l, e % 2 == 1);
    grid.near(pe, gap, [&](std::uint32_t o) {
      if (o <= e) return;
      const RawLine& m = chains[o / 2];
      if (m.kind != l.kind) return;
      if (o / 2 == e / 2 && l.points.size() <= 3) return;  // a chain too short to close
      const glm::dvec3 po = end_at(o);
      const double d = glm::length(po - pe);
      if (d < gap && continues(pe, te, po, tangent_at(m, o % 2 == 1))) links.push_back({d, e, o});
    });
  }
  std::sort(links.begin(), links.end(), [](const Link& x, const Link& y) { return x.d < y.d; });
  std::vector<std::ptrdiff_t> linked(ends, -1);
  for (const Link& k : links)
    if (linked[k.a] < 0 && linked[k.b] < 0) {
      linked[k.a] = static_cast<std::ptrdiff_t>(k.b);
      linked[k.b] = static_cast<std::ptrdiff_t>(k.a);
    }
  // Walk them: from a chain with a free end (a path), then what is left (loops).
  std::vector<char> taken(chains.size(), 0);
  std::vector<RawLine> joined;
  const auto walk_from = [&](std::size_t c, bool forward) {
    RawLine line;
    line.kind = chains[c].kind;
    line.origin = LineOrigin::Zeros;
    line.strength = kFullStrength;
    std::size_t here = c;
    bool fwd = forward;
    for (;;) {
      taken[here] = 1;
      const RawLine& piece = chains[here];
      if (fwd)
        line.points.insert(line.points.end(), piece.points.begin(), piece.points.end());
      else
        line.points.insert(line.points.end(), piece.points.rbegin(), piece.points.rend());
      const std::size_t out = 2 * here + (fwd ? 1 : 0);  // the end it leaves by
      if (linked[out] < 0) break;
      const auto follow = static_cast<std::size_t>(linked[out]);
      if (follow / 2 == c && taken[c] && follow == 2 * c + (forward ? 0 : 1)) {
        line.closed = true;  // back to where it began
        break;
      }
      if (taken[follow / 2]) break;
      here = follow / 2;
      fwd = follow % 2 == 0;  // entered by its front: along it
    }
    joined.push_back(std::move(line));
  };
  for (std::size_t c = 0; c < chains.size(); ++c) {
    if (taken[c] || chains[c].closed) continue;
    if (linked[2 * c] < 0)
      walk_from(c, true);
    else if (linked[2 * c + 1] < 0)
      walk_from(c, false);
  }
  for (std::size_t c = 0; c < chains.size(); ++c) {
    if (taken[c]) continue;
    if (chains[c].closed) {
      taken[c] = 1;
      joined.push_back(std::move(chains[c]));
    } else {
      walk_from(c, true);
    }
  }
  chains = std::move(joined);
  std::vector<RawLine> out;
  for (RawLine& line : chains) {
    double length = 0.0;
    for (std::size_t i = 1; i < line.points.size(); ++i) {
      length += glm::length(line.points[i].position - line.points[i - 1].position);
      line.points[i].arc = length;
    }
    if (line.closed)
      length += glm::length(line.points.front().position - line.points.back().position);
    // Long enough; or across the whole surface, from its edge to its edge:
    // a 2-D case's separation runs across its one cell's depth, however
    // short that is.
    const auto on_edge = [&](const TracePoint& p) {
      const auto b = f.barycentric(p.triangle, p.position);
      for (int k = 0; k < 3; ++k)  // edge k runs from corner k to k + 1: opposite corner k + 2
        if (f.neighbour(p.triangle, k) == kNoTriangle && std::abs(b[(k + 2) % 3]) < 1e-6)
          return true;
      return false;
    };
    const bool across = !line.closed && on_edge(line.points.front()) && on_edge(line.points.back());
    if (length >= scales.min_length || across) out.push_back(std::move(line));
  }
  return out;
}

PointGrid::PointGrid(double cell, const glm::dvec3& lo, const glm::dvec3& hi)
    : cell_(cell > 0.0 ? cell : 1.0) {
  double count = 1.0;
  std::int64_t dims[3];
  for (int k = 0; k < 3; ++k) {
    const double span = std::max(hi[k] - lo[k], 0.0);
    dims[k] = static_cast<std::int64_t>(std::floor(span / cell_)) + 1;
    count *= static_cast<double>(dims[k]);
  }
  if (!(count <= 4e6)) return;  // the hash map
  origin_ = lo;
  for (int k = 0; k < 3; ++k) dims_[k] = dims[k];
  dense_.resize(static_cast<std::size_t>(count));
}

void PointGrid::insert(const glm::dvec3& p, std::uint32_t item) {
  const Cell c = cell_of(p);
  if (!dense_.empty()) {
    dense_[static_cast<std::size_t>((c.z * dims_[1] + c.y) * dims_[0] + c.x)].push_back(item);
    return;
  }
  cells_[key(c.x, c.y, c.z)].push_back(item);
}

}  // namespace ibfvs::detail
