// HostFlow: the texture in a host's own framebuffer, one host render at a
// time (PyVista's actor drives it in VTK's context). Here a framebuffer with
// a magenta background stands for the host's: the texture goes where the
// surface is and nowhere else, behind the host's nearer depth; each render
// is one texture frame (three at the first); the host's colour table colours
// it; settings go on live or start afresh by their keys' rules; several
// processes render in steps (ParaView's mapper) as one renders; bad calls
// throw, naming the problem.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include <epoxy/gl.h>
#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "gl_fixture.h"
#include "ibfvs/core/geometry/displacement.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/objects.h"
#include "ibfvs/render/host_flow.h"

namespace ibfvs {
namespace {

class HostFlowGLTest : public test::GlTest {};

constexpr int kW = 160, kH = 120;

TriMesh swirl_torus() {
  TriMesh m = make_torus(1.0f, 0.4f, 96, 32);
  m.vectors.resize(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    m.vectors[i] = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), m.positions[i]);
  return m;
}

struct Host {
  gl::Texture2D colour, depth;
  gl::Framebuffer fb;
  Host()
      : colour(kW, kH, gl::Format::RGBA8, false),
        depth(kW, kH, gl::Format::Depth24, false),
        fb(gl::Framebuffer::create()) {
    fb.attach_color(0, colour);
    fb.attach_depth(depth);
    fb.finish(1);
    clear();
  }
  void clear() {
    fb.clear_color(0, glm::vec4(1.0f, 0.0f, 1.0f, 1.0f));  // magenta: the host's background
    fb.clear_depth();
  }
  std::vector<std::uint8_t> read() const {
    std::vector<std::uint8_t> out(static_cast<std::size_t>(kW) * kH * 4);
    fb.read_rgba8(0, kW, kH, out);
    return out;
  }
};

HostRender host_render(const TriMesh& mesh) {
  CameraParams params;
  params.elevation_deg = 35.0f;
  const Camera camera(mesh_bounds(mesh), params, static_cast<float>(kW) / kH);
  HostRender r;
  r.width = kW;
  r.height = kH;
  r.view = ViewState{camera.view(), camera.projection()};
  r.focal_distance = camera.distance_world();
  return r;
}

bool magenta(const std::vector<std::uint8_t>& p, std::size_t i) {
  return p[4 * i] == 255 && p[4 * i + 1] == 0 && p[4 * i + 2] == 255;
}

// One host render: its framebuffer bound and its viewport set, as VTK has them.
void draw(HostFlow& flow, Host& host, const HostRender& r) {
  host.fb.bind();
  gl::set_viewport(kW, kH);
  flow.render(r);
}

TEST_F(HostFlowGLTest, EachRenderDrawsAFrameWhereTheSurfaceIsAndOnlyThere) {
  const TriMesh mesh = swirl_torus();
  HostFlow flow;
  flow.set_surface(mesh, "the torus");
  Host host;
  const HostRender r = host_render(mesh);
  draw(flow, host, r);
  EXPECT_EQ(flow.frame(), kDefaultFramesPerStep);  // a new texture forms over a few
  std::vector<std::uint8_t> a;
  for (int k = 0; k < 20; ++k) {
    host.clear();
    draw(flow, host, r);
    if (k == 18) a = host.read();
  }
  EXPECT_EQ(flow.frame(), kDefaultFramesPerStep + 20);  // then one a render
  const std::vector<std::uint8_t> b = host.read();
  std::size_t background = 0, changed = 0;
  for (std::size_t i = 0; i < a.size() / 4; ++i) {
    EXPECT_EQ(magenta(a, i), magenta(b, i)) << "the surface moved in the image at " << i;
    if (magenta(b, i)) {
      ++background;
    } else {
      changed += std::abs(int(a[4 * i]) - int(b[4 * i])) > 8;
    }
  }
  const std::size_t n = a.size() / 4;
  EXPECT_GT(background, n / 5);      // the host's background stays off the surface
  EXPECT_LT(background, n * 4 / 5);  // and the surface covers a good part
  EXPECT_GT(changed, (n - background) / 10) << "the texture did not move between renders";
  flow.release();  // as a host does before its context goes
}

TEST_F(HostFlowGLTest, TheHostsNearerDepthHidesTheTexture) {
  const TriMesh mesh = swirl_torus();
  HostFlow flow;
  flow.set_surface(mesh, "the torus");
  Host host;
  const HostRender r = host_render(mesh);
  draw(flow, host, r);
  host.clear();
  // The host drew something nearer than everything over the left half.
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, kW / 2, kH);
  host.fb.clear_depth(0.0f);
  glDisable(GL_SCISSOR_TEST);
  draw(flow, host, r);
  const std::vector<std::uint8_t> p = host.read();
  std::size_t left = 0, right = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * kW + x;
      (x < kW / 2 ? left : right) += !magenta(p, i);
    }
  EXPECT_EQ(left, 0u);
  EXPECT_GT(right, static_cast<std::size_t>(kW * kH / 10));
  flow.release();
}

TEST_F(HostFlowGLTest, TheHostsTableColoursTheSurfaceAtThePositionsGiven) {
  TriMesh mesh = swirl_torus();
  std::vector<float> t(mesh.positions.size());
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = mesh.positions[i].x < 0.0f ? 0.0f : 1.0f;
  mesh.scalars[kHostColour] = t;
  HostFlow flow;
  flow.set_surface(mesh, "the torus");
  HostColours colours;
  for (int i = 0; i < 256; ++i) {
    const float u = static_cast<float>(i) / 255.0f;
    colours.table.emplace_back(1.0f - u, 0.2f, u);  // red to blue
  }
  flow.set_colours(colours);
  Host host;
  const HostRender r = host_render(mesh);
  for (int k = 0; k < 5; ++k) draw(flow, host, r);
  const std::vector<std::uint8_t> p = host.read();
  // The camera looks at the torus from +Z (azimuth 0): -X on the left.
  long red_left = 0, blue_right = 0, surface_left = 0, surface_right = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * kW + x;
      if (magenta(p, i) || std::abs(x - kW / 2) < kW / 10) continue;
      const int red = p[4 * i], blue = p[4 * i + 2];
      if (x < kW / 2) {
        ++surface_left;
        red_left += red > blue + 10;
      } else {
        ++surface_right;
        blue_right += blue > red + 10;
      }
    }
  ASSERT_GT(surface_left, 200);
  ASSERT_GT(surface_right, 200);
  EXPECT_GT(red_left, surface_left * 9 / 10);
  EXPECT_GT(blue_right, surface_right * 9 / 10);
  flow.release();
}

TEST_F(HostFlowGLTest, SettingsGoOnLiveOrStartAfreshByTheirKeysRules) {
  const TriMesh mesh = swirl_torus();
  HostFlow flow;
  flow.set_surface(mesh, "the torus");
  Host host;
  const HostRender r = host_render(mesh);
  for (int k = 0; k < 5; ++k) draw(flow, host, r);
  const int before = flow.frame();
  Scene s = flow.scene();
  s.alpha = 0.2f;
  s.scale = 3.0f;  // a new noise grid: the texture goes on over it
  flow.set_scene(s);
  draw(flow, host, r);
  EXPECT_EQ(flow.frame(), before + 1);
  // A key that needs the scene prepared again (the vectors reversed): the
  // session prepares it itself, the same session, the texture going on.
  const Session* session = flow.session();
  const ImageF texture = session->read_texture();
  s.reverse = true;
  flow.set_scene(s);
  EXPECT_EQ(flow.session()->read_texture().pixels, texture.pixels);  // nothing before the render
  draw(flow, host, r);
  EXPECT_EQ(flow.session(), session);
  EXPECT_TRUE(flow.session()->scene().scene.reverse);
  EXPECT_EQ(flow.frame(), before + 2);
  EXPECT_EQ(flow.session()->frame(), before + 2);
  // dt: the fastest vector moves the step at the focal point, in the
  // host's projection (world_per_pixel, the one rule).
  const Camera camera(
      mesh_bounds(mesh),
      [] {
        CameraParams p;
        p.elevation_deg = 35.0f;
        return p;
      }(),
      static_cast<float>(kW) / kH);
  float speed = 0.0f;
  for (const glm::vec3& v : mesh.vectors) speed = std::max(speed, glm::length(v));
  EXPECT_FLOAT_EQ(flow.session()->dt(), dt_for_step(s.step, speed, camera.world_per_pixel(kH)));
  s.seed = 99;  // a new seed: afresh
  flow.set_scene(s);
  draw(flow, host, r);
  EXPECT_EQ(flow.frame(), kDefaultFramesPerStep);
  s.alpha = 7.0f;
  EXPECT_THROW(flow.set_scene(s), SettingError);
  EXPECT_EQ(flow.scene().alpha, 0.2f);  // nothing changed
  flow.release();
}

// A host of several processes renders in steps: what each owes (pending),
// agreed (any flag, the fastest vector, every piece's bounds), begin, the
// frames with the host's compositing between them, finish. The steps give
// render()'s picture; an empty piece takes part in every frame without
// drawing; and a step change agreed by another piece reaches this one.
TEST_F(HostFlowGLTest, SeveralProcessesRenderInStepsAsOneRenders) {
  const TriMesh mesh = swirl_torus();
  const HostRender r = host_render(mesh);
  HostFlow one, stepped, empty;
  one.set_surface(mesh, "the torus");
  stepped.set_surface(mesh, "the torus");
  Host a, b, c;
  auto agree = [&](std::initializer_list<const HostFlow*> flows) {
    HostChanges all;
    for (const HostFlow* f : flows) {
      const HostChanges mine = f->pending(r.width, r.height);
      all.restart |= mine.restart;
      all.resize |= mine.resize;
      all.changed |= mine.changed;
      all.moved |= mine.moved;
      all.speed = std::max(all.speed, mine.speed);
      if (mine.bounds) all.bounds = mine.bounds;
    }
    return all;
  };
  EXPECT_FALSE(empty.pending(r.width, r.height).bounds);
  for (int render = 0; render < 6; ++render) {
    draw(one, a, r);
    const HostChanges all = agree({&stepped, &empty});
    EXPECT_EQ(all.restart, render == 0);
    HostRender rs = r;
    rs.defer_statistics = false;
    const int frames = stepped.begin(rs, all);
    EXPECT_EQ(empty.begin(rs, all), frames);
    EXPECT_EQ(frames, render == 0 ? kDefaultFramesPerStep : 1);
    for (int k = 0; k < frames; ++k) {
      stepped.frame(r.view);
      empty.frame(r.view);  // the host would composite here
    }
    b.fb.bind();
    gl::set_viewport(kW, kH);
    stepped.finish(r.origin);
    c.fb.bind();
    empty.finish(r.origin);
    EXPECT_TRUE(stepped.problem().empty() && empty.problem().empty());
  }
  EXPECT_EQ(stepped.frame(), one.frame());
  EXPECT_EQ(empty.frame(), one.frame());  // its frame count keeps step with the others
  EXPECT_EQ(empty.session(), nullptr);
  EXPECT_EQ(a.read(), b.read()) << "the steps drew another picture than render()";
  const std::vector<std::uint8_t> nothing = c.read();
  for (std::size_t i = 0; i < nothing.size() / 4; ++i)
    ASSERT_TRUE(magenta(nothing, i)) << "an empty piece drew at " << i;
  // A piece whose data changed: every piece takes the change alike (the
  // frames Frames Per Step owes), the one whose data did not included.
  TriMesh moved = mesh;
  for (glm::vec3& p : moved.positions) p += glm::vec3(0.01f, 0.0f, 0.0f);
  stepped.set_surface(moved, "the torus");
  const HostChanges all = agree({&stepped, &empty});
  EXPECT_TRUE(all.changed && all.moved && !all.restart);
  const int frames = stepped.begin(r, all);
  EXPECT_EQ(empty.begin(r, all), frames);
  EXPECT_GE(frames, 1);
  one.release();
  stepped.release();
  empty.release();
}

TEST_F(HostFlowGLTest, BadCallsThrowNamingTheProblem) {
  HostFlow flow;
  Host host;
  TriMesh mesh = swirl_torus();
  EXPECT_THROW(draw(flow, host, host_render(mesh)), InputError);  // no surface yet
  mesh.vectors.pop_back();
  try {
    flow.set_surface(mesh, "the torus");
    ADD_FAILURE() << "vectors of the wrong count were taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the torus"), std::string::npos) << e.what();
  }
  mesh = swirl_torus();
  mesh.positions[3].y = std::nanf("");
  EXPECT_THROW(flow.set_surface(mesh, "the torus"), InputError);
  mesh = swirl_torus();
  flow.set_surface(mesh, "the torus");
  context().release_current();  // no host context
  EXPECT_THROW(flow.render(host_render(mesh)), GraphicsError);
  context().make_current();
}

}  // namespace
}  // namespace ibfvs
