// The IBFVS pass on a real GL context, checked against properties that can
// fail: no noise on the background, alignment with a known flow, equality
// with the CPU reference, convergence, determinism (the features, camera
// motion, colouring and locking: renderer_features_gltest.cpp).

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
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/texture/reference.h"
#include "ibfvs/render/ibfvs_renderer.h"
#include "renderer_scenes.h"

namespace ibfvs::rendertest {
namespace {

TEST_F(RendererGLTest, NoNoiseOnTheBackground) {
  // Section 3.2, eq. 12: gamma = 0 off the surface. Checked with a coloured
  // background, a still and an orbiting camera, and both advection views.
  const glm::vec3 background(0.25f, 0.5f, 0.75f);  // exact in 16-bit float
  for (const AdvectView view : {AdvectView::Current, AdvectView::Previous}) {
    for (const float orbit : {0.0f, 2.0f}) {
      Scene s = sphere_scene("rotate:0,1,0", TangentMode::Project, 320.0f / 240.0f);
      RenderSettings settings;
      settings.width = 320;
      settings.height = 240;
      settings.background = background;
      settings.advect_view = view;
      IbfvsRenderer r(settings);
      r.set_mesh(s.mesh, s.field);
      const float dt = step_dt(s, 320, 240, 3.0f);
      for (int k = 0; k < 100; ++k) {
        s.camera.orbit(orbit);
        r.render_frame({s.camera.view(), s.camera.projection()}, dt);
      }
      const auto covered = r.read_coverage();
      const ImageU8 out = r.read_output();
      const ImageF tex = r.read_texture();
      std::size_t n_surface = 0, bad_out = 0, bad_tex = 0;
      for (std::size_t i = 0; i < covered.size(); ++i) {
        if (covered[i]) {
          ++n_surface;
          continue;
        }
        for (int c = 0; c < 3; ++c) {
          bad_out += out.pixels[i * 4 + c] != std::lround(background[c] * 255.0f);
          bad_tex += tex.pixels[i * 4 + c] != background[c];
        }
      }
      const double fraction = static_cast<double>(n_surface) / covered.size();
      EXPECT_GT(fraction, 0.3) << "the sphere should cover a good part of the image";
      EXPECT_LT(fraction, 0.9);
      EXPECT_EQ(bad_out, 0u) << "view " << static_cast<int>(view) << " orbit " << orbit;
      EXPECT_EQ(bad_tex, 0u) << "view " << static_cast<int>(view) << " orbit " << orbit;
    }
  }
}

// Rotation about the view axis, used in 3D: the image-space flow is circles
// about the image centre (the projection of a rotation about the optical axis).
double rotation_alignment(const TriMesh& mesh, const std::string& field, int frames,
                          RenderSettings settings, float step_pixels, bool print,
                          const char* name) {
  std::vector<glm::vec3> f = evaluate_field(mesh, FieldSpec::parse(field), TangentMode::Full3D);
  Camera cam(mesh_bounds(mesh), {}, 1.0f);
  IbfvsRenderer r(settings);
  r.set_mesh(mesh, f);
  const int w = settings.width, h = settings.height;
  const float dt = dt_for_pixel_step(mesh.positions, f, cam.view_projection(), w, h, step_pixels);
  for (int k = 0; k < frames; ++k) r.render_frame({cam.view(), cam.projection()}, dt);
  const ImageF tex = r.read_texture().select_channels(0, 1);
  const glm::vec2 c = project_to_pixels(cam.view_projection(), mesh_bounds(mesh).centre(), w, h);
  const double a = flow_alignment(
      tex, r.read_coverage(),
      [&](float x, float y) {
        const glm::vec2 d(x - c.x, y - c.y);
        // Too close to the centre, the direction is ill-defined.
        return glm::length(d) < 0.08f * w ? glm::vec2(0) : glm::vec2(-d.y, d.x);
      },
      4);
  if (print) std::printf("alignment A on %s: %.3f\n", name, a);
  return a;
}

TEST_F(RendererGLTest, TextureIsAlignedWithTheFlow) {
  RenderSettings settings;  // the command's defaults: s = 4, alpha 0.1, 3 px per frame
  settings.noise.scale = 4.0f;
  const TriMesh sphere = make_sphere(1.0f, 96, 192, 0.06f);
  const double aligned =
      rotation_alignment(sphere, "rotate:0,0,1", 120, settings, 3.0f, true, "bumpy sphere");
  // Measured 0.754 on llvmpipe; the image speed falls to zero towards the
  // centre, where streaks are short, so A stays well below 1.
  EXPECT_GT(aligned, 0.68);
  // The control: a still texture (zero field) has isotropic noise, A about 0.5.
  const double still = rotation_alignment(sphere, "uniform:0,0,0", 120, settings, 3.0f, true,
                                          "bumpy sphere, zero field");
  EXPECT_NEAR(still, 0.5, 0.05);

  const std::filesystem::path cow = std::filesystem::path(IBFVS_TEST_DATA_DIR) / "meshes/cow.off";
  if (!std::filesystem::exists(cow)) GTEST_SKIP() << "fetched data missing: " << cow;
  const double on_cow =
      rotation_alignment(read_mesh(cow), "rotate:0,0,1", 120, settings, 3.0f, true, "cow");
  EXPECT_GT(on_cow, 0.62);  // measured 0.693 on llvmpipe
}

// For every pixel of the flat view, where its pixel centre came from one frame
// earlier under the field v(p) = w x p + u (used in 3D).
BackwardMap flat_backward_map(int w, int h, glm::vec3 omega, glm::vec3 u, float dt) {
  BackwardMap m;
  m.width = w;
  m.height = h;
  m.covered.assign(static_cast<std::size_t>(w) * h, 1);
  m.source.resize(m.covered.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3 p(2.0f * (x + 0.5f) / w - 1.0f, 2.0f * (y + 0.5f) / h - 1.0f, 0.0f);
      const glm::vec3 q = p - (glm::cross(omega, p) + u) * dt;
      m.source[static_cast<std::size_t>(y) * w + x] = {(q.x + 1.0f) * 0.5f * w,
                                                       (q.y + 1.0f) * 0.5f * h};
    }
  return m;
}

TEST_F(RendererGLTest, EqualsTheCpuReferenceOnAFlatSquare) {
  // A square larger than the ortho view: every pixel is covered, so the
  // comparison has no silhouette to argue about. Rotation plus translation,
  // which is linear in position, so per-vertex interpolation is exact.
  constexpr int w = 192, h = 160;
  TriMesh square = make_square(2.0f, 24);
  const glm::vec3 omega(0, 0, 0.9f), u(0.15f, -0.05f, 0);
  std::vector<glm::vec3> field(square.vertex_count());
  for (std::size_t i = 0; i < field.size(); ++i)
    field[i] = glm::cross(omega, square.positions[i]) + u;
  const float dt = 0.012f;  // about 2.5 pixels per frame at the image corners
  for (const NoiseProfile profile : {NoiseProfile::Sine, NoiseProfile::Sawtooth}) {
    const RenderSettings settings = reference_settings(w, h, profile);
    IbfvsRenderer r(settings);
    r.set_mesh(square, field);
    ReferenceIbfvs ref(w, h, settings.background.x, settings.noise);
    const BackwardMap map = flat_backward_map(w, h, omega, u, dt);
    for (int k = 0; k < 50; ++k) {
      r.render_frame(flat_view(), dt);
      ref.step(map, k, settings.alpha);
    }
    const test::Difference d =
        test::difference(r.read_texture().select_channels(0, 1).pixels, ref.texture().pixels);
    const double max_diff = d.max, mean_diff = d.mean;
    std::printf("GPU vs CPU reference (%s, 50 frames): max %.4f mean %.5f\n",
                std::string(enum_name(profile)).c_str(), max_diff, mean_diff);
    // Sawtooth jumps from 1 to 0: a grid value at the jump may fall on either
    // side in GPU and CPU arithmetic, so its few pixels may differ more.
    EXPECT_LT(mean_diff, 0.003);
    // Measured on llvmpipe: max 0.0027, mean 0.0015 for both.
    EXPECT_LT(max_diff, profile == NoiseProfile::Sine ? 0.01 : 0.6);
  }
}

TEST_F(RendererGLTest, ImageNormalizedFlowEqualsTheCpuReference) {
  // Paper figure 2: normalised in image space every covered pixel moves
  // `step` pixels along the projected field, slow or fast. The CPU map moves
  // each pixel centre exactly so; the GPU normalises per vertex and
  // interpolates, equal up to the chord of the turning direction.
  constexpr int w = 160, h = 128;
  constexpr float step = 2.0f;
  TriMesh square = make_square(2.0f, 32);
  const glm::vec3 omega(0, 0, 0.25f), u(0.3f, 0.1f, 0);
  std::vector<glm::vec3> field(square.vertex_count());
  for (std::size_t i = 0; i < field.size(); ++i)
    field[i] = glm::cross(omega, square.positions[i]) + u;
  RenderSettings settings = reference_settings(w, h);
  settings.image_step = step;
  IbfvsRenderer r(settings);
  r.set_mesh(square, field);
  BackwardMap map;
  map.width = w;
  map.height = h;
  map.covered.assign(static_cast<std::size_t>(w) * h, 1);
  map.source.resize(map.covered.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3 p(2.0f * (x + 0.5f) / w - 1.0f, 2.0f * (y + 0.5f) / h - 1.0f, 0.0f);
      const glm::vec3 v = glm::cross(omega, p) + u;
      const glm::vec2 on_screen = glm::normalize(glm::vec2(v.x * w, v.y * h));
      map.source[static_cast<std::size_t>(y) * w + x] =
          glm::vec2(x + 0.5f, y + 0.5f) - step * on_screen;
    }
  ReferenceIbfvs ref(w, h, settings.background.x, settings.noise);
  for (int k = 0; k < 50; ++k) {
    r.render_frame(flat_view(), 1.0f);  // dt only gates the motion here
    ref.step(map, k, settings.alpha);
  }
  const test::Difference d =
      test::difference(r.read_texture().select_channels(0, 1).pixels, ref.texture().pixels);
  std::printf(
      "image-normalised flow, GPU vs CPU reference after 50 frames: max %.4f mean %.5f, "
      "%.3f%% of pixels off by more than 0.02\n",
      d.max, d.mean, 100.0 * d.above);
  // Measured on llvmpipe: mean 0.0014, max 0.093 on 0.02% of the pixels (the
  // chord and the probe's first-order step add to the 0.0027 of the plain
  // flow; at the image's inflow edge a source just inside the image for one
  // and just outside for the other takes fresh noise on one side only).
  EXPECT_LT(d.above, 0.002);
  EXPECT_LT(d.max, 0.15);
  EXPECT_LT(d.mean, 0.003);
  // And the normalisation matters: the plain flow with the same dt differs.
  settings.image_step = 0.0f;
  IbfvsRenderer plain(settings);
  plain.set_mesh(square, field);
  for (int k = 0; k < 50; ++k) plain.render_frame(flat_view(), 0.01f);
  EXPECT_GT(
      test::difference(plain.read_texture().select_channels(0, 1).pixels, ref.texture().pixels)
          .mean,
      0.02);
}

TEST_F(RendererGLTest, StillImageConvergesAsSection37Predicts) {
  // v_g = 0 and a still view: the change per frame shrinks like (1 - alpha)^N,
  // so from a first change c it is below eps after log(eps / c) / log(1 - alpha)
  // frames: N = 22 for the paper's c = alpha.
  constexpr int w = 128, h = 128;
  const float alpha = 0.1f, eps = 0.01f;
  const int n = static_cast<int>(std::ceil(std::log(eps / alpha) / std::log(1.0f - alpha)));
  EXPECT_EQ(n, 22);
  TriMesh square = make_square(2.0f, 8);
  const std::vector<glm::vec3> field(square.vertex_count(), glm::vec3(0.02f, 0.01f, 0));
  RenderSettings settings;
  settings.width = w;
  settings.height = h;
  settings.alpha = alpha;
  settings.noise.rate = 0.0f;
  settings.background = glm::vec3(0.0f);  // the worst case of the paper: from 0 to 1
  IbfvsRenderer r(settings);
  r.set_mesh(square, field);
  ImageF previous = r.read_texture().select_channels(0, 1);
  std::vector<double> change;
  for (int k = 0; k < 3 * n; ++k) {
    r.render_frame(flat_view(), 1.0f);
    const ImageF now = r.read_texture().select_channels(0, 1);
    double m = 0;
    for (std::size_t i = 0; i < now.pixels.size(); ++i)
      m = std::max(m, static_cast<double>(std::abs(now.pixels[i] - previous.pixels[i])));
    change.push_back(m);
    previous = now;
  }
  // The first frame fills the surface with fresh noise (nothing of the
  // background flows in); after it, change[k] = |F_t(k + 1) - F_t(k)| shrinks
  // by the factor 1 - alpha per frame.
  std::printf(
      "largest change per frame: step 0 %.4f, step 1 %.4f, step %d %.5f, step %d %.6f, "
      "step %d %.6f\n",
      change[0], change[1], n / 4, change[n / 4], n, change[n], 3 * n - 1, change[3 * n - 1]);
  EXPECT_GT(change[0], 0.9) << "fresh noise from the first frame";
  for (int k = 2; k < 3 * n; ++k)
    EXPECT_LE(change[k], std::pow(1.0 - alpha, k - 1) * change[1] + 2e-3) << "frame " << k;
  EXPECT_GT(change[n / 4], eps) << "still changing early on";
  // 16-bit float F_t: values near 1 are rounded to 2^-11, a difference to twice that.
  const int settled =
      1 + static_cast<int>(std::ceil(std::log(eps / change[1]) / std::log(1.0 - alpha)));
  ASSERT_LT(settled, 3 * n);
  EXPECT_LE(change[settled], eps + 1e-3) << "settled after " << settled << " frames";
  EXPECT_LE(change[3 * n - 1], 2e-3);
}

TEST_F(RendererGLTest, ZeroFieldSettlesOnTheNoise) {
  constexpr int w = 96, h = 64;
  TriMesh square = make_square(2.0f, 4);
  const std::vector<glm::vec3> zero(square.vertex_count(), glm::vec3(0));
  RenderSettings settings;
  settings.width = w;
  settings.height = h;
  settings.alpha = 0.3f;
  settings.noise.rate = 0.0f;
  settings.noise.profile = NoiseProfile::Sine;
  IbfvsRenderer r(settings);
  r.set_mesh(square, zero);
  for (int k = 0; k < 60; ++k) r.render_frame(flat_view(), 1.0f);
  const ImageF tex = r.read_texture().select_channels(0, 1);
  const NoiseGrid g(w, h, settings.noise);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      ASSERT_NEAR(tex.at(x, y), g.sample(x + 0.5f, y + 0.5f, 0), 2e-3f) << x << "," << y;
}

// Two big triangles tilted 65 degrees away, seen in strong perspective from
// (0, 0, 1.6): large depth variation, and clipped at the image edges.
glm::mat4 square_tilt() {
  return glm::rotate(glm::mat4(1.0f), glm::radians(-65.0f), glm::vec3(1, 0, 0));
}
TriMesh tilted_square() {
  TriMesh square = make_square(1.0f, 1);
  for (glm::vec3& p : square.positions) p = glm::vec3(square_tilt() * glm::vec4(p, 1.0f));
  for (glm::vec3& n : square.normals) n = glm::vec3(square_tilt() * glm::vec4(n, 0.0f));
  return square;
}
ViewState tilted_square_view() {
  return {glm::lookAt(glm::vec3(0, 0, 1.6f), glm::vec3(0), glm::vec3(0, 1, 0)),
          glm::perspective(glm::radians(60.0f), 1.0f, 0.05f, 10.0f)};
}

TEST_F(RendererGLTest, LargeTrianglesInPerspectiveDoNotDrift) {
  // Section 3.9: texture coordinates are screen positions, so they must be
  // interpolated linearly in screen space. Two big triangles, strongly tilted
  // in perspective, with a zero field: t(x) must be x exactly, and the
  // texture must settle on the noise. Perspective-correct interpolation would
  // bend t inside each triangle and make the texture crawl.
  constexpr int w = 160, h = 160;
  const TriMesh square = tilted_square();
  const std::vector<glm::vec3> zero(square.vertex_count(), glm::vec3(0));
  RenderSettings settings;
  settings.width = w;
  settings.height = h;
  settings.alpha = 0.3f;
  settings.noise.rate = 0.0f;
  settings.noise.profile = NoiseProfile::Sine;
  IbfvsRenderer r(settings);
  r.set_mesh(square, zero);
  const ViewState view = tilted_square_view();
  for (int k = 0; k < 60; ++k) r.render_frame(view, 1.0f);
  const ImageF tex = r.read_texture().select_channels(0, 1);
  const auto covered = r.read_coverage();
  const NoiseGrid g(w, h, settings.noise);
  double worst = 0;
  std::size_t n = 0;
  for (int y = 2; y < h - 2; ++y)
    for (int x = 2; x < w - 2; ++x) {
      bool inside = true;  // away from the silhouette, where background bleeds in
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) inside = inside && covered[(y + dy) * w + x + dx];
      if (!inside) continue;
      ++n;
      const double e = std::abs(double(tex.at(x, y)) - g.sample(x + 0.5f, y + 0.5f, 0));
      worst = std::max(worst, e);
    }
  std::printf("tilted square in perspective, zero field: %zu pixels, worst drift %.4f\n", n, worst);
  EXPECT_GT(n, static_cast<std::size_t>(w * h / 5));
  EXPECT_LT(worst, 0.01);
}

TEST_F(RendererGLTest, EqualsTheCpuReferenceOnLargeTrianglesInPerspective) {
  // The same tilted two-triangle square with a uniform flow in its plane. The
  // CPU reference finds, for every pixel, the point of the plane under it (a
  // ray-plane intersection), moves it back by v dt and projects it: eq. 13
  // evaluated exactly per pixel. Coverage is taken from the GPU (the test is
  // about the warp, not about rasterisation rules).
  constexpr int w = 160, h = 160;
  const glm::mat4 tilt = square_tilt();
  const TriMesh square = tilted_square();
  const glm::vec3 normal = square.normals[0];
  const glm::vec3 v = glm::vec3(tilt * glm::vec4(0.3f, 0.8f, 0.0f, 0.0f));  // in the plane
  const std::vector<glm::vec3> field(square.vertex_count(), v);
  const float dt = 0.01f;
  RenderSettings settings;
  settings.width = w;
  settings.height = h;
  settings.alpha = 0.12f;
  settings.noise.profile = NoiseProfile::Sine;
  settings.noise.rate = 0.03f;
  IbfvsRenderer r(settings);
  r.set_mesh(square, field);
  const glm::vec3 eye(0, 0, 1.6f);
  const ViewState view = tilted_square_view();
  const glm::mat4 vp = view.projection * view.view, inv = glm::inverse(vp);
  r.render_frame(view, dt);
  BackwardMap map;
  map.width = w;
  map.height = h;
  map.covered = r.read_coverage();
  map.source.resize(map.covered.size());
  float largest = 0.0f;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec4 far =
          inv * glm::vec4(2.0f * (x + 0.5f) / w - 1, 2.0f * (y + 0.5f) / h - 1, 1, 1);
      const glm::vec3 dir = glm::vec3(far) / far.w - eye;
      const glm::vec3 on_plane = eye - dir * (glm::dot(eye, normal) / glm::dot(dir, normal));
      const glm::vec2 src = project_to_pixels(vp, on_plane - v * dt, w, h);
      map.source[static_cast<std::size_t>(y) * w + x] = src;
      if (map.covered[static_cast<std::size_t>(y) * w + x])
        largest = std::max(largest, glm::length(src - glm::vec2(x + 0.5f, y + 0.5f)));
    }
  ReferenceIbfvs ref(w, h, settings.background.x, settings.noise);
  ref.step(map, 0, settings.alpha);
  for (int k = 1; k < 50; ++k) {
    r.render_frame(view, dt);
    ref.step(map, k, settings.alpha);
  }
  const test::Difference d =
      test::difference(r.read_texture().select_channels(0, 1).pixels, ref.texture().pixels);
  const double max_diff = d.max, mean_diff = d.mean;
  std::printf(
      "perspective, 2 large triangles, up to %.1f px per frame: GPU vs CPU max %.4f mean "
      "%.5f\n",
      largest, max_diff, mean_diff);
  EXPECT_GT(largest, 1.0f);
  EXPECT_LT(max_diff, 0.01);
  EXPECT_LT(mean_diff, 0.003);
}

TEST_F(RendererGLTest, ObjectSpaceNoiseEqualsTheCpuSolidNoise) {
  // Section 3.6: G from a 3D lattice at the surface point. A still, zero field
  // settles on it; the flat square at z = 0 under the unit ortho view puts
  // pixel (x, y) at the point (2(x + 0.5)/w - 1, 2(y + 0.5)/h - 1, 0).
  constexpr int w = 96, h = 64;
  TriMesh square = make_square(2.0f, 4);
  const std::vector<glm::vec3> zero(square.vertex_count(), glm::vec3(0));
  RenderSettings settings;
  settings.width = w;
  settings.height = h;
  settings.alpha = 0.3f;
  settings.noise.rate = 0.0f;
  settings.noise.profile = NoiseProfile::Sine;
  settings.noise.seed = 7;
  settings.object_noise = true;
  settings.object_cell = 0.11f;
  IbfvsRenderer r(settings);
  r.set_mesh(square, zero);
  for (int k = 0; k < 60; ++k) r.render_frame(flat_view(), 1.0f);
  const ImageF tex = r.read_texture().select_channels(0, 1);
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float px = 2.0f * (x + 0.5f) / w - 1.0f, py = 2.0f * (y + 0.5f) / h - 1.0f;
      worst = std::max(worst, std::abs(double(tex.at(x, y)) -
                                       solid_noise(settings.noise, 0.11f, px, py, 0.0f, 0)));
    }
  std::printf("object-space noise, GPU vs CPU: worst %.4f\n", worst);
  EXPECT_LT(worst, 3e-3);
}

TEST_F(RendererGLTest, SameSeedSameImage) {
  const auto render = [](std::uint32_t seed) {
    Scene s = sphere_scene("rotate:0,1,0", TangentMode::Project);
    RenderSettings settings;
    settings.width = settings.height = 128;
    settings.noise.seed = seed;
    IbfvsRenderer r(settings);
    r.set_mesh(s.mesh, s.field);
    for (int k = 0; k < 30; ++k) r.render_frame({s.camera.view(), s.camera.projection()}, 0.01f);
    return r.read_output().pixels;
  };
  const auto a = render(1), b = render(1), c = render(2);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

}  // namespace
}  // namespace ibfvs::rendertest
