// The topology overlay (scene key overlay = topology) against its CPU
// reference: a sphere whose flow spirals out of its poles onto its equator,
// seen from above the equator by a camera that turns about the poles' axis. The separation line is
// drawn where the reference says the surface shows it, not behind the sphere; the foci's glyphs at
// the pole; the texture elsewhere as without the overlay.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "gl_fixture.h"
#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/render/session.h"
#include "ibfvs/render/topology_overlay.h"

namespace ibfvs {
namespace {

class TopologyOverlayGLTest : public test::GlTest {};

constexpr int kW = 256, kH = 256;

// The globe jittered along itself, turning about +Y and pulled onto y = 0.
TriMesh spiral_globe() {
  TriMesh m = make_globe(4);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> d(-0.01f, 0.01f);
  for (glm::vec3& p : m.positions) p = glm::normalize(p + glm::vec3(d(rng), d(rng), d(rng)));
  m.normals.clear();
  const glm::vec3 axis(0.0f, 1.0f, 0.0f);
  m.vectors.clear();
  for (const glm::vec3& p : m.positions) {
    const float z = glm::dot(axis, p);
    m.vectors.push_back(glm::cross(axis, p) - z * (axis - z * p));
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
  const glm::vec3 red = rgb_of(10), pink = rgb_of(5);
  std::size_t line_ref = 0, line_drawn = 0, focus_ref = 0, focus_drawn = 0;
  std::size_t red_out = 0, red_placed = 0, changed = 0, changed_placed = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int k = ref[static_cast<std::size_t>(y) * kW + x];
      const std::uint8_t* p = px(with.picture, x, y);
      if (k == 10 && !in_legend(x, y)) {
        ++line_ref;
        line_drawn += near_colour(p, red, 40) || near_colour(p, 0.35f * red, 20);  // or its rim
      }
      if (k == 5) {
        ++focus_ref;
        focus_drawn += near_colour(p, pink, 40) || near_colour(p, glm::vec3(13.0f), 20);
      }
      if (in_legend(x, y)) continue;
      if (near_colour(p, red, 30)) {
        ++red_out;
        red_placed += near_kind(ref, x, y, 10, 3);
      }
      const std::uint8_t* q = px(without.picture, x, y);
      if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2]) {
        ++changed;
        bool placed = false;
        for (int kind : {5, 10}) placed = placed || near_kind(ref, x, y, kind, 8);
        changed_placed += placed;
      }
    }
  // The front half of the equator crosses the picture.
  EXPECT_GT(line_ref, static_cast<std::size_t>(kW / 2)) << line_ref;
  EXPECT_GE(line_drawn, line_ref * 95 / 100) << line_drawn << " of " << line_ref;
  EXPECT_GT(focus_ref, 5u);
  EXPECT_GE(focus_drawn, focus_ref * 9 / 10) << focus_drawn << " of " << focus_ref;
  // Red only on the line the reference sees: none behind the sphere.
  EXPECT_GT(red_out, 0u);
  EXPECT_GE(red_placed, red_out * 98 / 100) << red_placed << " of " << red_out;
  // The texture itself as without the overlay, but under the features.
  EXPECT_GT(changed, 0u);
  EXPECT_EQ(changed_placed, changed);
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
