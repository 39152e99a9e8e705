// The IBFVS pass's features on a real GL context: switched live, the grey
// texture in one channel, the texture attached to the surface under camera
// motion, particles, colour and beta by scalars, unsteady fields, surface
// images, dragging and locking, the topological decomposition, bad input.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gl_fixture.h"
#include "helpers.h"
#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/geometry/displacement.h"
#include "ibfvs/core/image/image_analysis.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/texture/display.h"
#include "ibfvs/core/texture/reference.h"
#include "ibfvs/render/ibfvs_renderer.h"
#include "ibfvs/render/pass_settings.h"
#include "renderer_scenes.h"

namespace ibfvs::rendertest {
namespace {

TEST_F(RendererGLTest, FeaturesSwitchedLiveMatchAFreshRenderer) {
  // Each combination of features is its own compiled program. Switching
  // colouring on for some frames and off again must leave F_t untouched and
  // give, once off, the picture a renderer that never switched gives.
  Scene s = sphere_scene("rotate:0,1,0", TangentMode::Project);
  std::vector<float> height(s.mesh.vertex_count());
  for (std::size_t i = 0; i < height.size(); ++i) height[i] = s.mesh.positions[i].y;
  RenderSettings plain;
  plain.width = plain.height = 128;
  const ViewState view{s.camera.view(), s.camera.projection()};
  IbfvsRenderer a(plain), b(plain);
  for (IbfvsRenderer* r : {&a, &b}) {
    r->set_mesh(s.mesh, s.field);
    r->set_scalars(height, height);
  }
  RenderSettings coloured = plain;
  coloured.use_color = coloured.use_beta = true;
  coloured.color_range = coloured.beta_range = {-1.0f, 1.0f};
  coloured.alpha = 0.2f;
  bool differed = false;
  for (int k = 0; k < 30; ++k) {
    a.render_frame(view, 0.01f);
    if (k == 10) b.update_settings(coloured);
    if (k == 12) {
      coloured.alpha = plain.alpha;  // alpha back, colour still on
      b.update_settings(coloured);
    }
    if (k == 20) b.update_settings(plain);
    b.render_frame(view, 0.01f);
    if (k == 15) differed = a.read_output().pixels != b.read_output().pixels;
  }
  EXPECT_TRUE(differed) << "colouring should change the picture while it is on";
  EXPECT_NE(a.read_texture().pixels, b.read_texture().pixels)
      << "alpha 0.2 for two frames changes F_t";
  // The same again without the alpha change: F_t and F end equal.
  IbfvsRenderer c(plain), d(plain);
  for (IbfvsRenderer* r : {&c, &d}) {
    r->set_mesh(s.mesh, s.field);
    r->set_scalars(height, height);
  }
  coloured.alpha = plain.alpha;
  for (int k = 0; k < 30; ++k) {
    c.render_frame(view, 0.01f);
    if (k == 10) d.update_settings(coloured);
    if (k == 20) d.update_settings(plain);
    d.render_frame(view, 0.01f);
  }
  EXPECT_EQ(c.read_texture().pixels, d.read_texture().pixels);
  EXPECT_EQ(c.read_output().pixels, d.read_output().pixels);
}

TEST_F(RendererGLTest, GreyTextureInOneChannelEqualsTheColourTexture) {
  // With a grey background F_t is kept in one channel; a coloured background
  // switches it to four, keeping its content. The same frames give the same
  // values either way.
  Scene s = sphere_scene("rotate:0,1,0", TangentMode::Project);
  RenderSettings settings;
  settings.width = settings.height = 128;
  const ViewState view{s.camera.view(), s.camera.projection()};
  IbfvsRenderer mono(settings), colour(settings);
  EXPECT_EQ(mono.texture_channels(), 1);
  RenderSettings tinted = settings;
  tinted.background = {0.5f, 0.25f, 0.75f};
  colour.update_settings(tinted);
  EXPECT_EQ(colour.texture_channels(), 4);
  colour.update_settings(settings);  // grey again: four channels until reset()
  EXPECT_EQ(colour.texture_channels(), 4);
  for (IbfvsRenderer* r : {&mono, &colour}) {
    r->set_mesh(s.mesh, s.field);  // resets: back to one channel
    EXPECT_EQ(r->texture_channels(), 1);
  }
  colour.update_settings(tinted);
  colour.update_settings(settings);
  ASSERT_EQ(colour.texture_channels(), 4);
  for (int k = 0; k < 40; ++k) {
    mono.render_frame(view, 0.01f);
    colour.render_frame(view, 0.01f);
  }
  const ImageF a = mono.read_texture(), b = colour.read_texture();
  float largest = 0.0f, spread = 0.0f;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    largest = std::max(largest, std::abs(a.pixels[i] - b.pixels[i]));
    spread = std::max(spread, std::abs(a.pixels[i] - 0.5f));
  }
  const ImageU8 fa = mono.read_output(), fb = colour.read_output();
  int largest_output = 0;
  for (std::size_t i = 0; i < fa.pixels.size(); ++i)
    largest_output = std::max(largest_output, std::abs(int(fa.pixels[i]) - int(fb.pixels[i])));
  std::printf("one vs four channels: F_t within %.5f, F within %d/255\n", largest, largest_output);
  EXPECT_LT(largest, 1e-3f);
  EXPECT_GT(spread, 0.2f) << "the texture should hold noise, not only the background";
  EXPECT_LE(largest_output, 1);

  // Switching to colour keeps what F_t holds, spread to grey RGB.
  const ImageF before = mono.read_texture();
  mono.update_settings(tinted);
  EXPECT_EQ(mono.texture_channels(), 4);
  EXPECT_EQ(mono.read_texture().pixels, before.pixels);
}

// Correlation of the final texture with the texture before a camera orbit,
// (a) at the same pixel (texture fixed in image space) and (b) at the pixel
// where the same surface point was (texture fixed on the surface).
struct Attachment {
  double image_fixed, surface_fixed;
};

Attachment orbit_attachment(AdvectView view) {
  constexpr int w = 192, h = 192;
  Scene s = sphere_scene("uniform:0,0,0", TangentMode::Project);
  RenderSettings settings;
  settings.width = w;
  settings.height = h;
  settings.alpha = 0.2f;
  settings.noise.rate = 0.0f;
  settings.advect_view = view;
  IbfvsRenderer r(settings);
  r.set_mesh(s.mesh, s.field);
  for (int k = 0; k < 40; ++k) r.render_frame({s.camera.view(), s.camera.projection()}, 0.0f);
  const ImageF before = r.read_texture().select_channels(0, 1);
  const glm::mat4 vp0 = s.camera.view_projection();
  settings.alpha = 0.0f;  // no fresh ink: only transport
  r.update_settings(settings);
  for (int k = 0; k < 8; ++k) {
    s.camera.orbit(1.5f);
    r.render_frame({s.camera.view(), s.camera.projection()}, 0.0f);
  }
  const ImageF after = r.read_texture().select_channels(0, 1);
  const ImageF depth = r.read_depth();
  const glm::mat4 inv = glm::inverse(s.camera.view_projection());
  std::vector<float> final_values, same_pixel, same_point;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // The middle of the sphere, away from the silhouette and newly exposed parts.
      if (std::hypot(x + 0.5f - w / 2.0f, y + 0.5f - h / 2.0f) > 0.3f * w) continue;
      const float d = depth.at(x, y);
      if (!(d < 1.0f)) continue;
      // Unproject the pixel to its surface point, then project it with the old view.
      const glm::vec2 src = project_to_pixels(vp0, unproject_pixel(inv, x, y, d, w, h), w, h);
      const int sx = static_cast<int>(src.x), sy = static_cast<int>(src.y);
      if (sx < 0 || sy < 0 || sx >= w || sy >= h) continue;
      final_values.push_back(after.at(x, y));
      same_pixel.push_back(before.at(x, y));
      same_point.push_back(before.at(sx, sy));
    }
  const std::vector<std::uint8_t> mask(final_values.size(), 1);
  return {test::correlation(final_values, same_pixel, mask),
          test::correlation(final_values, same_point, mask)};
}

TEST_F(RendererGLTest, PreviousViewKeepsTheTextureOnTheSurface) {
  const Attachment current = orbit_attachment(AdvectView::Current);
  const Attachment previous = orbit_attachment(AdvectView::Previous);
  std::printf(
      "orbit 12 deg, correlation image-fixed / surface-fixed: current %.3f / %.3f, "
      "previous %.3f / %.3f\n",
      current.image_fixed, current.surface_fixed, previous.image_fixed, previous.surface_fixed);
  EXPECT_GT(current.image_fixed, 0.95);  // the 2003 behaviour: the texture swims
  EXPECT_LT(current.surface_fixed, 0.5);
  EXPECT_GT(previous.surface_fixed, 0.8);  // ours: it stays on the surface
  EXPECT_LT(previous.image_fixed, 0.5);
}

TEST_F(RendererGLTest, SpikesAddedGiveSparseBrightParticles) {
  Scene s = sphere_scene("rotate:0,1,0", TangentMode::Project);
  RenderSettings settings;
  settings.width = settings.height = 160;
  settings.noise.profile = NoiseProfile::Spike;
  settings.noise.spike_width = 0.02f;
  settings.inject = InjectMode::Add;
  settings.background = glm::vec3(0.0f);
  IbfvsRenderer r(settings);
  r.set_mesh(s.mesh, s.field);
  for (int k = 0; k < 60; ++k) r.render_frame({s.camera.view(), s.camera.projection()}, 0.005f);
  const ImageF tex = r.read_texture().select_channels(0, 1);
  const auto covered = r.read_coverage();
  std::vector<float> values;
  for (std::size_t i = 0; i < covered.size(); ++i)
    if (covered[i]) values.push_back(tex.pixels[i]);
  std::sort(values.begin(), values.end());
  const float median = values[values.size() / 2], top = values[values.size() * 99 / 100];
  std::printf("particles: median %.3f, 99th percentile %.3f\n", median, top);
  EXPECT_LT(median, 0.2f) << "mostly dark";
  EXPECT_GT(top, 0.6f) << "with bright particles";
}

TEST_F(RendererGLTest, ScalarsColourTheSurfaceAndModulateBeta) {
  // The flat square, coloured by x through viridis, with beta modulated by x:
  // purple and no texture on the left, yellow and textured on the right.
  constexpr int w = 128, h = 64;
  TriMesh square = make_square(2.0f, 8);
  std::vector<float> x(square.vertex_count());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = square.positions[i].x;
  const std::vector<glm::vec3> field(square.vertex_count(), glm::vec3(0.1f, 0.05f, 0.0f));
  RenderSettings settings;
  settings.width = w;
  settings.height = h;
  settings.beta = 0.8f;
  settings.use_color = true;
  settings.color_range = {-1.0f, 1.0f};
  settings.use_beta = true;
  settings.beta_range = {-0.5f, 1.0f};
  IbfvsRenderer r(settings);
  r.set_mesh(square, field);
  r.set_scalars(x, x);
  for (int k = 0; k < 40; ++k) r.render_frame(flat_view(), 0.05f);
  const ImageU8 out = r.read_output();
  const auto column_stats = [&](int x0, int x1, glm::dvec3& mean, double& spread) {
    glm::dvec3 sum(0), sum2(0);
    int n = 0;
    for (int y = 8; y < h - 8; ++y)
      for (int xx = x0; xx < x1; ++xx) {
        const glm::dvec3 c(out.at(xx, y, 0), out.at(xx, y, 1), out.at(xx, y, 2));
        sum += c;
        sum2 += c * c;
        ++n;
      }
    mean = sum / double(n);
    const glm::dvec3 var = sum2 / double(n) - mean * mean;
    spread = std::sqrt(var.x + var.y + var.z);
  };
  glm::dvec3 left, right;
  double left_spread = 0, right_spread = 0;
  column_stats(2, 12, left, left_spread);
  column_stats(w - 12, w - 2, right, right_spread);
  std::printf("left mean %.0f,%.0f,%.0f spread %.1f; right mean %.0f,%.0f,%.0f spread %.1f\n",
              left.x, left.y, left.z, left_spread, right.x, right.y, right.z, right_spread);
  EXPECT_GT(left.z, left.x);    // viridis(0): dark purple, more blue than red
  EXPECT_GT(right.x, right.z);  // viridis(1): yellow
  EXPECT_GT(right.y, right.z);
  EXPECT_LT(left_spread, 3.0);                        // beta 0: shading only, no texture
  EXPECT_GT(right_spread, 8.0 * left_spread + 10.0);  // textured
  EXPECT_THROW(r.set_scalars(std::vector<float>(3), {}), InputError);
  settings.color_range = {1.0f, 1.0f};
  EXPECT_THROW(settings.validate(), InputError);
}

TEST_F(RendererGLTest, UnsteadyFieldHalfwayIsTheMeanField) {
  // Two time steps mixed 0.5 on the GPU advect exactly like their mean.
  Scene s = sphere_scene("rotate:0,1,0", TangentMode::Project);
  const auto other =
      evaluate_field(s.mesh, FieldSpec::parse("uniform:0.3,0.8,0"), TangentMode::Project);
  std::vector<glm::vec3> mean(other.size());
  for (std::size_t i = 0; i < mean.size(); ++i) mean[i] = 0.5f * (s.field[i] + other[i]);
  RenderSettings settings;
  settings.width = settings.height = 96;
  const auto render = [&](bool steps) {
    IbfvsRenderer r(settings);
    r.set_mesh(s.mesh, steps ? s.field : mean);
    if (steps) {
      r.set_field_steps(s.field, other);
      r.set_field_mix(0.5f);
    }
    for (int k = 0; k < 30; ++k) r.render_frame({s.camera.view(), s.camera.projection()}, 0.01f);
    return r.read_texture().select_channels(0, 1).pixels;
  };
  const auto a = render(true), b = render(false);
  EXPECT_LT(test::difference(a, b).max, 2e-3);
  // And mix 0 is the first step: different from the mean.
  IbfvsRenderer r(settings);
  r.set_mesh(s.mesh, s.field);
  r.set_field_steps(s.field, other);
  r.set_field_mix(0.0f);
  for (int k = 0; k < 30; ++k) r.render_frame({s.camera.view(), s.camera.projection()}, 0.01f);
  const auto c = r.read_texture().select_channels(0, 1).pixels;
  EXPECT_GT(test::difference(c, b).max, 0.1);
  EXPECT_THROW(r.set_field_steps(s.field, std::vector<glm::vec3>(3)), InputError);
}

TEST_F(RendererGLTest, SurfaceImageIsMappedByLongitudeAndLatitude) {
  // West red, east blue, the northern hemisphere's top rows green: seen from
  // +Z (longitude 0), the left of the sphere is red, the right blue, the top green.
  Scene s = sphere_scene("uniform:0,0,0", TangentMode::Project);
  ImageU8 map(64, 32, 4);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      std::uint8_t* p = &map.pixels[(static_cast<std::size_t>(y) * 64 + x) * 4];
      p[0] = x < 32 ? 255 : 0;
      p[2] = x < 32 ? 0 : 255;
      p[1] = y >= 24 ? 255 : 0;  // north of 45 degrees
      p[3] = 255;
    }
  RenderSettings settings;
  settings.width = settings.height = 96;
  settings.beta = 0.0f;
  IbfvsRenderer r(settings);
  r.set_mesh(s.mesh, s.field);
  r.set_surface_image(map, glm::vec3(0));
  r.render_frame({s.camera.view(), s.camera.projection()}, 0.0f);
  const ImageU8 out = r.read_output();
  const auto px = [&](int x, int y) {
    return glm::ivec3(out.at(x, y, 0), out.at(x, y, 1), out.at(x, y, 2));
  };
  EXPECT_GT(px(30, 48).x, 3 * px(30, 48).z) << "west is red";
  EXPECT_GT(px(66, 48).z, 3 * px(66, 48).x) << "east is blue";
  const glm::ivec3 north = px(48, 88);
  EXPECT_GT(north.y, north.x) << "the north is green";
  EXPECT_GT(north.y, north.z) << "the north is green";
  r.set_surface_image(ImageU8{}, glm::vec3(0));  // off again: the plain surface colour
  r.render_frame({s.camera.view(), s.camera.projection()}, 0.0f);
  const ImageU8 plain = r.read_output();
  EXPECT_NEAR(plain.at(30, 48, 0), plain.at(30, 48, 2), 20);
}

TEST_F(RendererGLTest, ShiftImageMovesTheTextureWithThePointer) {
  // Section 3.7's option (b): while dragging, F_t moves with the mouse. With
  // no flow and no fresh ink (alpha 0) one shifted frame is F_t moved by
  // exactly that many pixels.
  constexpr int w = 96, h = 64;
  TriMesh square = make_square(2.0f, 4);
  const std::vector<glm::vec3> zero(square.vertex_count(), glm::vec3(0));
  RenderSettings settings;
  settings.width = w;
  settings.height = h;
  settings.alpha = 0.0f;
  IbfvsRenderer r(settings);
  r.set_mesh(square, zero);
  r.fill_texture_with_cell_colors(3);
  r.render_frame(flat_view(), 0.0f);
  const ImageF before = r.read_texture().select_channels(0, 1);
  r.shift_image({7.0f, -3.0f});
  r.render_frame(flat_view(), 0.0f);
  const ImageF after = r.read_texture().select_channels(0, 1);
  double worst = 0.0;
  for (int y = 8; y < h - 8; ++y)
    for (int x = 8; x < w - 8; ++x)
      worst = std::max(worst, static_cast<double>(std::abs(
                                  after.pixels[static_cast<std::size_t>(y) * w + x] -
                                  before.pixels[static_cast<std::size_t>(y + 3) * w + x - 7])));
  EXPECT_LT(worst, 1e-3);
  // The shift is for one frame: the next one stands still again.
  r.render_frame(flat_view(), 0.0f);
  EXPECT_LT(test::difference(r.read_texture().select_channels(0, 1).pixels, after.pixels).max,
            1e-3);
}

TEST_F(RendererGLTest, NoiseGridDrawnOnlyWhereTheSurfaceCanReadIt) {
  // The grid pass draws only the cells that the surface's screen box can
  // read (with the sharpening's reach and the bilinear footprints). A square
  // in the middle, and the same square with a speck in a corner that
  // stretches the box over the whole image, so that the whole grid is drawn:
  // F_t and F must be equal bit for bit, with pixel-fine and coarser noise,
  // and after the noise is dragged.
  constexpr int w = 160, h = 120;
  const TriMesh square = make_square(0.4f, 16);
  std::vector<glm::vec3> field(square.vertex_count());
  for (std::size_t i = 0; i < field.size(); ++i)
    field[i] = glm::cross(glm::vec3(0, 0, 1.5f), square.positions[i]) + glm::vec3(0.2f, 0, 0);
  TriMesh speck = square;
  const auto first = static_cast<std::uint32_t>(speck.positions.size());
  for (const glm::vec2 p :
       {glm::vec2(-0.98f, -0.98f), glm::vec2(-0.94f, -0.98f), glm::vec2(-0.98f, -0.94f)}) {
    speck.positions.emplace_back(p, 0.0f);
    if (!speck.normals.empty()) speck.normals.emplace_back(0, 0, 1);
  }
  speck.triangles.push_back({first, first + 1, first + 2});
  std::vector<glm::vec3> speck_field = field;
  speck_field.resize(speck.vertex_count(), glm::vec3(0));
  for (const float scale : {1.0f, 3.0f}) {
    RenderSettings settings;  // the default look, without the contrast stage's
    settings.width = w;       // statistics (the speck's pixels would count)
    settings.height = h;
    settings.contrast = 0.0f;
    settings.noise.scale = scale;
    IbfvsRenderer a(settings), b(settings);
    a.set_mesh(square, field);
    b.set_mesh(speck, speck_field);
    for (int k = 0; k < 24; ++k) {
      if (k == 12)
        for (IbfvsRenderer* r : {&a, &b}) r->shift_image({2.5f, -1.5f});
      for (IbfvsRenderer* r : {&a, &b}) r->render_frame(flat_view(), 0.01f);
    }
    const ImageF ta = a.read_texture(), tb = b.read_texture();
    const ImageU8 fa = a.read_output(), fb = b.read_output();
    int texture_differs = 0, output_differs = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (x < 12 && y < 12) continue;  // the speck
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        texture_differs += ta.pixels[4 * i] != tb.pixels[4 * i] ? 1 : 0;
        for (int c = 0; c < 3; ++c)
          output_differs += fa.pixels[4 * i + c] != fb.pixels[4 * i + c] ? 1 : 0;
      }
    EXPECT_EQ(texture_differs, 0) << "noise scale " << scale;
    EXPECT_EQ(output_differs, 0) << "noise scale " << scale;
  }
}

TEST_F(RendererGLTest, TapTextureStoresWhatDisplayHDescribes) {
  // The shader's 8-bit tap texture and core/texture/display.h, which
  // ReferenceIbfvs and write_texture_raw use, agree: the depth under the
  // frame's map, the direction of the recorded displacement, and nothing
  // off the surface.
  const Scene s = sphere_scene("rotate:0.3,1,0", TangentMode::Project);
  RenderSettings settings;
  settings.width = settings.height = 128;
  settings.filter_length = 16.0f;
  settings.sharpen = 4.0f;
  IbfvsRenderer r(settings);
  r.set_mesh(s.mesh, s.field);
  r.record_flow(true);
  const ViewState view{s.camera.view(), s.camera.projection()};
  for (int k = 0; k < 12; ++k) r.render_frame(view, step_dt(s, 128, 128, 1.5f));
  const glm::vec2 map = tap_depth_map(view.projection);
  ASSERT_GT(map.y, 0.0f);
  const ImageF raw = r.read_texture_raw();
  const ImageF flow = r.read_flow();
  constexpr int c = IbfvsRenderer::kRawChannels;
  int surface = 0, moving = 0;
  for (std::size_t i = 0; i < flow.pixels.size() / 2; ++i) {
    const float* p = &raw.pixels[c * i];
    if (!(p[1] > -255.0f)) {
      EXPECT_EQ(p[5], 0.0f) << i;                                 // no depth, no direction
      EXPECT_LT(glm::length(glm::vec2(p[2], p[3])), 0.01f) << i;  // 0.5 stores as 128/255
      continue;
    }
    ++surface;
    // F_t's depth is rounded to 16 bits: the stored one within a step
    // (steps of about 0.3% of the depth here: the planes hug the sphere).
    const float expected = unorm8(encode_tap_depth(p[1], map));
    EXPECT_NEAR(p[5], expected, 1.01f / 255.0f) << i;
    const glm::vec2 f(flow.pixels[2 * i], flow.pixels[2 * i + 1]);
    if (glm::length(f) < 0.3f) continue;
    ++moving;
    const glm::vec2 d(p[2], p[3]);
    EXPECT_NEAR(glm::length(d), 1.0f, 0.01f) << i;
    EXPECT_GT(glm::dot(glm::normalize(d), glm::normalize(f)), std::cos(glm::radians(1.0f))) << i;
  }
  EXPECT_GT(surface, 128 * 128 / 3);
  EXPECT_GT(moving, surface / 2);
}

TEST_F(RendererGLTest, DeferredPassEqualsTheSinglePass) {
  // The default look's pass split in two (the surface per pixel, then the
  // rest once per pixel, the display pass's work included) against the
  // single pass and the display pass, as the browser page runs them: the
  // same F_t, and F within the rounding of the seed the single pass hands
  // the display pass. The camera turns and its clipping planes move every
  // frame, so the taps' depth map changes from one frame to the next (the
  // filter reads the last frame's taps under that frame's map); missing
  // colour scalars keep the surface colour.
  constexpr int w = 128, h = 128;
  const Scene s = sphere_scene("rotate:0.3,1,0", TangentMode::Project);
  RenderSettings base;
  base.width = w;
  base.height = h;
  RenderSettings settings = ibfvs::scene_settings(ibfvs::Scene{}, base);
  ASSERT_TRUE(shaders::deferred_pass(shaders::features_for(settings, false, false, false)));
  settings.use_color = true;
  settings.color_range = {-1.0f, 1.0f};
  std::vector<float> height(s.mesh.vertex_count());
  for (std::size_t i = 0; i < height.size(); ++i)
    height[i] = s.mesh.positions[i].x > 0.6f ? std::nanf("") : s.mesh.positions[i].y;
  IbfvsRenderer deferred(settings), single(settings);
  single.allow_deferred_pass(false);
  for (IbfvsRenderer* r : {&deferred, &single}) {
    r->set_mesh(s.mesh, s.field);
    r->set_scalars(height, {});
  }
  const glm::vec3 centre(0.0f);
  for (int k = 0; k < 40; ++k) {
    const float a = glm::radians(2.0f * static_cast<float>(k));
    const glm::vec3 eye(3.0f * std::sin(a), 0.5f, 3.0f * std::cos(a));
    const float near = k % 2 == 0 ? 1.0f : 1.6f, far = k % 3 == 0 ? 5.0f : 9.0f;
    const ViewState view{glm::lookAt(eye, centre, glm::vec3(0, 1, 0)),
                         glm::perspective(glm::radians(40.0f), 1.0f, near, far)};
    for (IbfvsRenderer* r : {&deferred, &single}) r->render_frame(view, 1.0f);
  }
  const ImageF ta = deferred.read_texture_raw(), tb = single.read_texture_raw();
  int surface = 0;
  for (std::size_t i = 0; i < ta.pixels.size(); i += IbfvsRenderer::kRawChannels) {
    if (tb.pixels[i + 1] > -255.0f) ++surface;
    for (int c = 0; c < IbfvsRenderer::kRawChannels; ++c)
      ASSERT_NEAR(ta.pixels[i + c], tb.pixels[i + c], 1e-3f) << i << " " << c;
  }
  EXPECT_GT(surface, w * h / 3);
  const ImageU8 fa = deferred.read_output(), fb = single.read_output();
  int close = 0, far_off = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < fa.pixels.size(); i += 4) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(fa.pixels[i + c] - fb.pixels[i + c]));
    sum += d;
    close += d <= 6 ? 1 : 0;
    far_off += d > 40 ? 1 : 0;
  }
  const int pixels = w * h;
  EXPECT_GT(close, pixels * 99 / 100);
  EXPECT_LT(far_off, pixels / 500);
  EXPECT_LT(sum / pixels, 1.0);
}

TEST_F(RendererGLTest, LockedTextureStaysOnTheSurface) {
  constexpr int w = 160, h = 160;
  Scene s = sphere_scene("rotate:0,1,0", TangentMode::Project);
  RenderSettings settings;
  settings.width = w;
  settings.height = h;
  settings.beta = 1.0f;  // F = F_t: the output shows the texture itself
  IbfvsRenderer r(settings);
  r.set_mesh(s.mesh, s.field);
  for (int k = 0; k < 40; ++k) r.render_frame({s.camera.view(), s.camera.projection()}, 0.01f);
  const ImageF locked = r.read_texture().select_channels(0, 1);
  const glm::mat4 vp0 = s.camera.view_projection();
  r.lock();
  for (int k = 0; k < 10; ++k) {
    s.camera.orbit(1.5f);
    r.render_frame({s.camera.view(), s.camera.projection()}, 0.01f);
  }
  EXPECT_EQ(r.read_texture().select_channels(0, 1).pixels, locked.pixels) << "F_t unchanged";
  const ImageU8 out = r.read_output();
  const ImageF depth = r.read_depth();
  const glm::mat4 inv = glm::inverse(s.camera.view_projection());
  std::vector<float> seen, expected;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (std::hypot(x + 0.5f - w / 2.0f, y + 0.5f - h / 2.0f) > 0.3f * w) continue;
      const float d = depth.at(x, y);
      if (!(d < 1.0f)) continue;
      const glm::vec2 src = project_to_pixels(vp0, unproject_pixel(inv, x, y, d, w, h), w, h);
      seen.push_back(out.at(x, y, 0) / 255.0f);
      expected.push_back(locked.at(static_cast<int>(src.x), static_cast<int>(src.y)));
    }
  const double c = test::correlation(seen, expected, std::vector<std::uint8_t>(seen.size(), 1));
  std::printf("locked, 15 degree orbit: correlation with the texture carried on the surface %.3f\n",
              c);
  EXPECT_GT(c, 0.95);
  r.unlock();
  r.render_frame({s.camera.view(), s.camera.projection()}, 0.01f);
  EXPECT_NE(r.read_texture().select_channels(0, 1).pixels, locked.pixels) << "unlocked: moving";
}

float two_hills(float x, float y) {
  return std::exp(-6.0f * ((x + 0.4f) * (x + 0.4f) + y * y)) +
         0.8f * std::exp(-6.0f * ((x - 0.45f) * (x - 0.45f) + (y - 0.1f) * (y - 0.1f)));
}

// Which hill steepest ascent from (x, y) reaches: 0 or 1, or -1 if it leaves
// the square first.
int basin(float x, float y) {
  for (int i = 0; i < 4000; ++i) {
    const float e = 1e-3f;
    const float gx = (two_hills(x + e, y) - two_hills(x - e, y)) / (2 * e);
    const float gy = (two_hills(x, y + e) - two_hills(x, y - e)) / (2 * e);
    const float g = std::hypot(gx, gy);
    if (g < 1e-4f) break;
    x += 0.002f * gx / g;
    y += 0.002f * gy / g;
    if (std::abs(x) > 1.0f || std::abs(y) > 1.0f) return -1;
  }
  if (std::hypot(x + 0.4f, y) < 0.05f) return 0;
  if (std::hypot(x - 0.45f, y - 0.1f) < 0.05f) return 1;
  return -1;
}

TEST_F(RendererGLTest, TopologicalDecompositionMatchesTheAscentBasins) {
  // Section 4.1, figure 7: alpha = 0, F_t starts as random colours per noise
  // cell, the flow runs downhill (normalised). Each pixel ends with the colour
  // of the summit that steepest ascent from it reaches.
  constexpr int w = 192, h = 192;
  const TriMesh hills = make_height_field(two_hills, 1.0f, 128);
  const auto field = evaluate_field(hills, FieldSpec::parse("gradient:down:0,0,1:normalize"),
                                    TangentMode::Project);
  CameraParams top;
  top.orthographic = true;
  Camera cam(mesh_bounds(hills), top, 1.0f);
  RenderSettings settings;
  settings.width = w;
  settings.height = h;
  settings.alpha = 0.0f;
  settings.noise.scale = 6.0f;
  IbfvsRenderer r(settings);
  r.set_mesh(hills, field);
  r.fill_texture_with_cell_colors(3);
  const float dt = dt_for_pixel_step(hills.positions, field, cam.view_projection(), w, h, 2.0f);
  for (int k = 0; k < 120; ++k) r.render_frame({cam.view(), cam.projection()}, dt);
  const ImageF tex = r.read_texture();
  const auto colour_at = [&](const glm::vec3& p) {
    const glm::vec2 px = project_to_pixels(cam.view_projection(), p, w, h);
    const int x = static_cast<int>(px.x), y = static_cast<int>(px.y);
    return glm::vec3(tex.at(x, y, 0), tex.at(x, y, 1), tex.at(x, y, 2));
  };
  const glm::vec3 summit[2] = {colour_at({-0.4f, 0.0f, two_hills(-0.4f, 0.0f)}),
                               colour_at({0.45f, 0.1f, two_hills(0.45f, 0.1f)})};
  ASSERT_GT(glm::length(summit[0] - summit[1]), 0.2f) << "pick a seed with distinct colours";
  const glm::mat4 inv = glm::inverse(cam.view_projection());
  const ImageF depth = r.read_depth();
  const auto surface_point = [&](int x, int y) {
    const glm::vec3 p = unproject_pixel(inv, x, y, depth.at(x, y), w, h);
    return glm::vec2(p.x, p.y);
  };
  std::size_t agree = 0, counted = 0;
  for (int y = 6; y < h - 6; y += 2)
    for (int x = 6; x < w - 6; x += 2) {
      if (!(depth.at(x, y) < 1.0f)) continue;
      const glm::vec2 q = surface_point(x, y);
      const int b = basin(q.x, q.y);
      if (b < 0) continue;
      bool interior = true;  // away from basin borders (6 pixels)
      for (const glm::ivec2 o :
           {glm::ivec2(6, 0), glm::ivec2(-6, 0), glm::ivec2(0, 6), glm::ivec2(0, -6)}) {
        const glm::vec2 n = surface_point(x + o.x, y + o.y);
        interior = interior && basin(n.x, n.y) == b;
      }
      if (!interior) continue;
      const glm::vec3 c(tex.at(x, y, 0), tex.at(x, y, 1), tex.at(x, y, 2));
      ++counted;
      agree += glm::length(c - summit[b]) < glm::length(c - summit[1 - b]);
    }
  const double agreement = static_cast<double>(agree) / counted;
  std::printf("topology: %zu pixels away from basin borders, %.1f%% carry their summit's colour\n",
              counted, 100.0 * agreement);
  EXPECT_GT(counted, 1000u);
  EXPECT_GE(agreement, 0.95);
}

TEST_F(RendererGLTest, RejectsMismatchedInput) {
  RenderSettings settings;
  settings.width = settings.height = 32;
  IbfvsRenderer r(settings);
  TriMesh sq = make_square(1.0f, 2);
  std::vector<glm::vec3> short_field(3);
  EXPECT_THROW(r.set_mesh(sq, short_field), InputError);
  settings.alpha = 1.5f;
  EXPECT_THROW(IbfvsRenderer bad(settings), InputError);
}

}  // namespace
}  // namespace ibfvs::rendertest
