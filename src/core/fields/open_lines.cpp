// Open separation and attachment lines (line_finder.h): seeded on the ridges
// of the field's convergence rate, traced while their neighbours keep
// converging onto them, then pruned.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "line_finder.h"

namespace ibfvs::detail {

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
  // A seed on a line found, or on a trace tried, is passed over.
  const auto passed_over = [&](const Seed& seed) {
    const glm::dvec3& p = seed.at.position;
    if (line_grid_.near(p, s_.seed_gap + f_.mean_edge(),
                        [&](std::uint32_t m) { return marks_[m].distance(p) <= s_.seed_gap; }))
      return true;
    return tried.near(seed.at.position, s_.merge, [&](std::uint32_t k) {
      return glm::length(tried_at[k] - seed.at.position) <= s_.merge;
    });
  };
  // The seeds one at a time, strongest first, each line found seen by the
  // traces after it; in batches, each batch's traces ahead found in
  // parallel against the lines found before it, then taken in order: a
  // seed that what its batch found before it passes over is passed over,
  // and a trace that came near a line found since is traced again. The
  // same lines as one at a time.
  constexpr std::size_t kBatch = 32;
  std::vector<std::size_t> batch;
  std::vector<TraceResult> aheads;
  std::vector<double> ahead_strength;
  std::vector<std::optional<TraceResult>> behinds;
  // The strength of a trace ahead that joins no line (a line's, or none).
  const auto strength_ahead = [&](const TraceResult& ahead, const Seed& seed) {
    return ahead.met == Met::Line
               ? o_.min_strength
               : strength(to_line(ahead, seed.kind == LineKind::Separation ? 1 : -1, seed.kind,
                                  LineOrigin::Open));
  };
  for (std::size_t next = 0; next < seeds.size();) {
    batch.clear();
    for (; next < seeds.size() && batch.size() < kBatch; ++next)
      if (!passed_over(seeds[next])) batch.push_back(next);
    aheads.assign(batch.size(), TraceResult{});
    ahead_strength.assign(batch.size(), 0.0);
    behinds.assign(batch.size(), std::nullopt);
    const std::size_t marks_before = marks_.size(), tried_before = tried_at.size();
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t b = 0; b < static_cast<std::int64_t>(batch.size()); ++b) {
      const auto k = static_cast<std::size_t>(b);
      const Seed& seed = seeds[batch[k]];
      aheads[k] = follow(seed.at, seed.kind == LineKind::Separation ? 1 : -1, seed.kind, Mode::Open,
                         std::nullopt);
      ahead_strength[k] = strength_ahead(aheads[k], seed);
      // Its extension behind, where the line may be kept: it sees no line.
      if (aheads[k].met != Met::Cycle &&
          (aheads[k].met == Met::Line || ahead_strength[k] >= o_.min_strength - 1.5))
        behinds[k] = follow(seed.at, seed.kind == LineKind::Separation ? -1 : 1, seed.kind,
                            Mode::Extension, std::nullopt);
    }
    for (std::size_t b = 0; b < batch.size(); ++b) {
      const Seed& seed = seeds[batch[b]];
      // (Passed over for what its batch's seeds before it found.)
      if ((marks_.size() > marks_before || tried_at.size() > tried_before) && passed_over(seed))
        continue;
      const int sense = seed.kind == LineKind::Separation ? 1 : -1;
      TraceResult ahead = std::move(aheads[b]);
      if (marks_.size() > marks_before && sees_marks_from(ahead, marks_before)) {
        ahead = follow(seed.at, sense, seed.kind, Mode::Open, std::nullopt);
        ahead_strength[b] = strength_ahead(ahead, seed);
      }
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
      if (ahead.met != Met::Line && ahead_strength[b] < o_.min_strength - 1.5) {
        for (const TracePoint& p : ahead.trace.points) {
          tried.insert(p.position, static_cast<std::uint32_t>(tried_at.size()));
          tried_at.push_back(p.position);
        }
        continue;
      }
      const TraceResult behind =
          behinds[b] ? std::move(*behinds[b])
                     : follow(seed.at, -sense, seed.kind, Mode::Extension, std::nullopt);
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
  // The line grid's cells are narrower than these searches. The marks of
  // the skeleton (every line but the open ones), and of the open lines of
  // each kind, apart: a line is looked for beside those it may shadow.
  const double wide_cell = std::max(2.0 * s_.disk, beside_radius) + f_.mean_edge();
  PointGrid skeleton(wide_cell, f_.lo(), f_.hi()), open_separation(wide_cell, f_.lo(), f_.hi()),
      open_attachment(wide_cell, f_.lo(), f_.hi());
  const auto grid_of = [&](const RawLine& l) -> PointGrid& {
    if (l.origin != LineOrigin::Open) return skeleton;
    return l.kind == LineKind::Separation ? open_separation : open_attachment;
  };
  for (std::uint32_t m = 0; m < marks_.size(); ++m) {
    PointGrid& g = grid_of(lines_[marks_[m].line]);
    g.insert(marks_[m].position, m);
    if (g.key_of(marks_[m].position) != g.key_of(marks_[m].to)) g.insert(marks_[m].to, m);
  }
  const auto nearest = [&](const glm::dvec3& p, std::uint32_t self, double radius) {
    std::optional<std::uint32_t> best;
    double best_d = radius;
    for (const PointGrid* g : {&skeleton, &open_separation, &open_attachment})
      g->near(p, radius + f_.mean_edge(), [&](std::uint32_t m) {
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
      // Beside a line of the skeleton of either kind (within the finder's
      // resolution), or a stronger open one of its own kind closer than
      // half the significance scale: one feature. (Every fourth point: they
      // lie a quarter of an edge apart.) Decided as soon as more than half
      // of them are beside one, or cannot be.
      const PointGrid& own = a.kind == LineKind::Separation ? open_separation : open_attachment;
      const std::size_t samples = (a.points.size() + 3) / 4;
      std::size_t beside = 0, seen = 0;
      for (std::size_t k = 0; k < a.points.size(); k += 4, ++seen) {
        if (2 * beside > samples || 2 * (beside + samples - seen) <= samples) break;
        const glm::dvec3& p = a.points[k].position;
        const bool near = skeleton.near(p, s_.seed_gap + f_.mean_edge(), [&](std::uint32_t m) {
          return !dropped[marks_[m].line] && marks_[m].distance(p) <= s_.seed_gap;
        }) || own.near(p, beside_radius + f_.mean_edge(), [&](std::uint32_t m) {
          const Mark& mk = marks_[m];
          if (mk.line == i || dropped[mk.line] || lines_[mk.line].strength < a.strength)
            return false;
          return mk.distance(p) <= beside_radius;
        });
        beside += near;
      }
      drop = 2 * beside > samples;
    }
    dropped[i] = drop;
  }
  std::vector<RawLine> kept;
  for (std::uint32_t i = 0; i < lines_.size(); ++i)
    if (!dropped[i]) kept.push_back(std::move(lines_[i]));
  lines_ = std::move(kept);
}

}  // namespace ibfvs::detail
