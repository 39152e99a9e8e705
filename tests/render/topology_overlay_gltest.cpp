// The topology overlay (scene key overlay = topology) against its CPU
// reference: a sphere whose flow spirals out of its poles onto its equator,
// seen from above the equator by a camera that turns about the poles' axis. The separation line is
// drawn where the reference says the surface shows it, not behind the sphere; the foci's glyphs at
// the pole; the texture elsewhere as without the overlay.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "gl_fixture.h"
#include "helpers.h"
#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/fields/topology_morph.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/render/session.h"
#include "ibfvs/render/topology_overlay.h"

namespace ibfvs {
namespace {

class TopologyOverlayGLTest : public test::GlTest {};

constexpr int kW = 256, kH = 256;

// The globe jittered along itself, turning about +Y and pulled onto y = c.
TriMesh spiral_globe(float c = 0.0f) {
  TriMesh m = make_globe(4);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> d(-0.01f, 0.01f);
  for (glm::vec3& p : m.positions) {
    const float z = d(rng), y = d(rng), x = d(rng);  // one by one: the same with any compiler
    p = glm::normalize(p + glm::vec3(x, y, z));
  }
  m.normals.clear();
  const glm::vec3 axis(0.0f, 1.0f, 0.0f);
  m.vectors.clear();
  for (const glm::vec3& p : m.positions) {
    const float z = glm::dot(axis, p);
    m.vectors.push_back(glm::cross(axis, p) - (z - c) * (axis - z * p));
  }
  return m;
}

Scene spiral_scene(Overlay overlay) {
  Scene s;
  s.width = kW;
  s.height = kH;
  s.overlay = overlay;
  s.orbit = 4.0f;  // the camera turns 4 degrees a frame: the features stay on the surface
  apply_setting(s, "camera", "0,25,1.4");
  apply_setting(s, "field", "file");
  return s;
}

struct Drawn {
  ImageU8 picture;
  ImageF depth;
  ViewState view;
  FlowTopology topology;
};

Drawn draw(Overlay overlay, int frames) {
  Session session(prepare_scene(spiral_scene(overlay), spiral_globe(), "spiral"));
  for (int k = 0; k < frames; ++k) session.advance();
  Drawn d{session.read_output(),
          session.renderer().read_depth(),
          ViewState{session.camera().view(), session.camera().projection()},
          {}};
  if (session.overlay_topology()) d.topology = *session.overlay_topology();
  return d;
}

bool near_colour(const std::uint8_t* px, glm::vec3 rgb, int tolerance) {
  return std::abs(px[0] - static_cast<int>(rgb.x)) <= tolerance &&
         std::abs(px[1] - static_cast<int>(rgb.y)) <= tolerance &&
         std::abs(px[2] - static_cast<int>(rgb.z)) <= tolerance;
}

glm::vec3 rgb_of(int kind) {
  for (const KindStyle& k : kind_styles())
    if (k.kind == kind) return {k.rgb[0], k.rgb[1], k.rgb[2]};
  return glm::vec3(0.0f);
}

// Whether some pixel within `r` of (x, y) is `kind` in the reference.
bool near_kind(const std::vector<int>& ref, int x, int y, int kind, int r) {
  for (int j = std::max(0, y - r); j <= std::min(kH - 1, y + r); ++j)
    for (int i = std::max(0, x - r); i <= std::min(kW - 1, x + r); ++i)
      if (ref[static_cast<std::size_t>(j) * kW + i] == kind) return true;
  return false;
}

// The separation lines as drawn against the reference's: of the pixels
// where the reference has one (outside the legend), how many show it; of
// the red pixels, how many lie within 3 pixels of the reference's.
struct LineMatch {
  std::size_t ref = 0, drawn = 0, red = 0, placed = 0;
};
LineMatch match_lines(const ImageU8& picture, const std::vector<int>& ref,
                      const std::function<bool(int, int)>& in_legend) {
  const glm::vec3 red = rgb_of(10);
  LineMatch m;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (in_legend(x, y)) continue;
      const std::uint8_t* p = &picture.pixels[(static_cast<std::size_t>(y) * kW + x) *
                                              static_cast<std::size_t>(picture.channels)];
      if (ref[static_cast<std::size_t>(y) * kW + x] == 10) {
        ++m.ref;
        m.drawn += near_colour(p, red, 40) || near_colour(p, 0.35f * red, 20);  // or its rim
      }
      if (near_colour(p, red, 30)) {
        ++m.red;
        m.placed += near_kind(ref, x, y, 10, 3);
      }
    }
  return m;
}

TEST_F(TopologyOverlayGLTest, DrawsWhatItsReferenceSeesAndLeavesTheTexture) {
  const Drawn with = draw(Overlay::Topology, 12);
  const Drawn without = draw(Overlay::None, 12);
  ASSERT_EQ(with.topology.count(LineKind::Separation), 1u);
  ASSERT_EQ(with.topology.count(CriticalKind::RepellingFocus), 2u);
  const std::vector<int> ref =
      overlay_reference(with.topology, with.view.view, with.view.projection, {kW, kH}, with.depth);
  // The legend's box, from the geometry: left alone below.
  glm::vec2 legend(0.0f);
  for (const OverlayVertex& v : build_overlay(with.topology, {kW, kH}).vertices)
    if (v.shape >= kOverlayPixels) legend = glm::max(legend, glm::vec2(v.point));
  const auto in_legend = [&](int x, int y) { return x <= legend.x + 1 && y <= legend.y + 1; };
  ASSERT_GT(legend.x, 40.0f);  // "separation line (1)" and the foci
  const auto px = [&](const ImageU8& im, int x, int y) {
    return &im.pixels[(static_cast<std::size_t>(y) * kW + x) *
                      static_cast<std::size_t>(im.channels)];
  };
  const glm::vec3 pink = rgb_of(5);
  const LineMatch lines = match_lines(with.picture, ref, in_legend);
  std::size_t focus_ref = 0, focus_drawn = 0, changed = 0, changed_placed = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int k = ref[static_cast<std::size_t>(y) * kW + x];
      const std::uint8_t* p = px(with.picture, x, y);
      if (k == 5) {
        ++focus_ref;
        focus_drawn += near_colour(p, pink, 40) || near_colour(p, glm::vec3(13.0f), 20);
      }
      if (in_legend(x, y)) continue;
      const std::uint8_t* q = px(without.picture, x, y);
      if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2]) {
        ++changed;
        bool placed = false;
        for (int kind : {5, 10}) placed = placed || near_kind(ref, x, y, kind, 8);
        changed_placed += placed;
      }
    }
  // The front half of the equator crosses the picture.
  EXPECT_GT(lines.ref, static_cast<std::size_t>(kW / 2)) << lines.ref;
  EXPECT_GE(lines.drawn, lines.ref * 95 / 100) << lines.drawn << " of " << lines.ref;
  EXPECT_GT(focus_ref, 5u);
  EXPECT_GE(focus_drawn, focus_ref * 9 / 10) << focus_drawn << " of " << focus_ref;
  // Red only on the line the reference sees: none behind the sphere.
  EXPECT_GT(lines.red, 0u);
  EXPECT_GE(lines.placed, lines.red * 98 / 100) << lines.placed << " of " << lines.red;
  // The texture itself as without the overlay, but under the features.
  EXPECT_GT(changed, 0u);
  EXPECT_EQ(changed_placed, changed);
}

// The mean height (y) of the separation lines' points, and their count.
std::pair<double, std::size_t> line_height(const FlowTopology& t) {
  double sum = 0.0;
  std::size_t n = 0, lines = 0;
  for (const FeatureLine& l : t.lines.lines) {
    if (l.kind != LineKind::Separation) continue;
    ++lines;
    for (const LinePoint& p : l.points) {
      sum += p.position.y;
      ++n;
    }
  }
  return {n ? sum / static_cast<double>(n) : 0.0, lines};
}

TEST_F(TopologyOverlayGLTest, OnASeriesTheFeaturesMoveWithTheStepsAndKeepTheirIds) {
  // Two steps: the limit cycle at y = 0, then at y = 0.15 (latitude 8.6
  // degrees, within the two scales, 0.21, that a feature may move in a step
  // and keep its id); four frames a step. Halfway through step 0 the line
  // is drawn halfway (y = 0.075, as its reference there says), with the
  // same id it has at step 1.
  const test::TempDir dir;
  write_ply(spiral_globe(0.0f), dir / "spiral_0.ply");
  write_ply(spiral_globe(0.15f), dir / "spiral_1.ply");
  Scene s = spiral_scene(Overlay::Topology);
  s.mesh = (dir / "spiral_*.ply").string();
  s.frames_per_step = 4;
  s.orbit = 0.0f;
  Session session(prepare_scene(s));
  std::vector<FlowTopology> seen;
  std::vector<Drawn> drawn;
  for (int k = 0; k < 5; ++k) {  // mixes 0, 0.25, 0.5, 0.75 of step 0; step 1
    session.advance();
    ASSERT_NE(session.overlay_topology(), nullptr);
    seen.push_back(*session.overlay_topology());
    if (k == 2)
      drawn.push_back({session.read_output(), session.renderer().read_depth(),
                       ViewState{session.camera().view(), session.camera().projection()},
                       seen.back()});
  }
  for (int k = 0; k < 5; ++k) {
    const auto [height, count] = line_height(seen[static_cast<std::size_t>(k)]);
    ASSERT_EQ(count, 1u) << "frame " << k;
    // Moving between the steps' lines, in proportion (the found lines lie within
    // 0.01 of y = 0 and 0.15).
    const double expected = k < 4 ? 0.0375 * k : 0.15;
    EXPECT_NEAR(height, expected, 0.015) << "frame " << k;
    EXPECT_EQ(seen[static_cast<std::size_t>(k)].lines.lines[0].id, seen[0].lines.lines[0].id)
        << "frame " << k;
  }
  for (int k = 0; k < 5; ++k) {
    ASSERT_EQ(seen[static_cast<std::size_t>(k)].critical.points.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i)
      EXPECT_EQ(seen[static_cast<std::size_t>(k)].critical.points[i].id,
                seen[0].critical.points[i].id);
  }
  // The pass draws the line where its reference has it halfway.
  const Drawn& half = drawn[0];
  const std::vector<int> ref =
      overlay_reference(half.topology, half.view.view, half.view.projection, {kW, kH}, half.depth);
  glm::vec2 legend(0.0f);
  for (const OverlayVertex& v : build_overlay(half.topology, {kW, kH}).vertices)
    if (v.shape >= kOverlayPixels) legend = glm::max(legend, glm::vec2(v.point));
  const auto in_legend = [&](int x, int y) { return x <= legend.x + 1 && y <= legend.y + 1; };
  const LineMatch m = match_lines(half.picture, ref, in_legend);
  EXPECT_GT(m.ref, static_cast<std::size_t>(kW / 2)) << m.ref;
  EXPECT_GE(m.drawn, m.ref * 95 / 100) << m.drawn << " of " << m.ref;
  EXPECT_GE(m.placed, m.red * 98 / 100) << m.placed << " of " << m.red;
}

TEST_F(TopologyOverlayGLTest, TheSignificanceIsTheScenesAndChangesLive) {
  // The closed orbit gathers its neighbours by e^(2 pi) a turn (pulled at
  // rate 1): kept at the default least strength 2, not at 7.
  Session session(prepare_scene(spiral_scene(Overlay::Topology), spiral_globe(), "spiral"));
  session.advance();
  ASSERT_NE(session.overlay_topology(), nullptr);
  EXPECT_EQ(session.overlay_topology()->count(LineKind::Separation), 1u);
  Scene strict = session.scene().scene;
  apply_setting(strict, "min_strength", "7");
  EXPECT_EQ(session.set(strict), SetResult::Applied);
  session.advance();
  EXPECT_EQ(session.overlay_topology()->count(LineKind::Separation), 0u);
  EXPECT_EQ(session.overlay_topology()->count(CriticalKind::RepellingFocus), 2u);
}

TEST_F(TopologyOverlayGLTest, BetweenStepsTheLegendShowsEachStepsCounts) {
  FlowTopology a, b;
  CriticalPoint p;
  p.id = 0;
  a.critical.points = {p};
  p.kind = CriticalKind::AttractingNode;
  p.id = 1;
  b.critical.points = {p};
  const TopologyMorph m = morph_steps(a, b);
  // The legend: the first step's counts, then the second's.
  std::size_t first = 0, second = 0;
  for (const OverlayVertex& v : build_overlay(m, {200, 100}).vertices) {
    first += v.shape >= kOverlayPixels && v.span == static_cast<float>(MorphSpan::FirstHalf);
    second += v.shape >= kOverlayPixels && v.span == static_cast<float>(MorphSpan::SecondHalf);
  }
  EXPECT_GT(first, 0u);
  EXPECT_GT(second, 0u);
}

TEST_F(TopologyOverlayGLTest, TheGeometryHasAQuadForEachPieceAndALegend) {
  FlowTopology t;
  CriticalPoint p;
  p.kind = CriticalKind::Saddle;
  t.critical.points = {p, p};
  FeatureLine closed;
  closed.kind = LineKind::Attachment;
  closed.closed = true;
  closed.points.resize(5);
  t.lines.lines = {closed};
  const OverlayGeometry g = build_overlay(t, {200, 100});
  std::size_t segments = 0, glyphs = 0, legend = 0;
  for (std::size_t v = 0; v < g.vertices.size(); v += 4) {
    const float s = g.vertices[v].shape;
    segments += s == kOverlayLine;
    glyphs += s >= 1.0f && s <= 6.0f;
    legend += s >= kOverlayPixels;
  }
  EXPECT_EQ(segments, 5u);  // a closed line of five points: five pieces
  EXPECT_EQ(glyphs, 2u);
  EXPECT_GT(legend, 10u);  // a box, two swatches and the letters of two labels
  EXPECT_EQ(g.indices.size(), g.vertices.size() / 4 * 6);
  EXPECT_TRUE(build_overlay(FlowTopology{}, {200, 100}).vertices.empty());
}

}  // namespace
}  // namespace ibfvs
