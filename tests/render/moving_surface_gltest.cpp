// Surfaces that move and data that changes: the advection includes the
// surface's own motion (against the CPU reference, and a body turning under
// a still camera against the camera turning around the still body), another
// mesh keeps the texture in the image, and the session carries the texture
// through a change of data, a resize and a rebuild.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "helpers.h"
#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/texture/reference.h"
#include "ibfvs/render/session.h"
#include "renderer_scenes.h"

namespace ibfvs::rendertest {
namespace {

// The correlation of two one-channel images over the pixels both cover.
double correlation(const std::vector<float>& a, const std::vector<float>& b,
                   const std::vector<std::uint8_t>& mask_a,
                   const std::vector<std::uint8_t>& mask_b) {
  std::vector<std::uint8_t> both(mask_a.size());
  for (std::size_t i = 0; i < both.size(); ++i) both[i] = mask_a[i] && mask_b[i];
  return test::correlation(a, b, both);
}

std::vector<float> grey(const ImageF& rgba) {
  return rgba.select_channels(0, 1).pixels;
}

std::vector<float> grey(const ImageU8& rgba) {
  std::vector<float> out(rgba.pixels.size() / 4);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = rgba.pixels[4 * i] / 255.0f;
  return out;
}

glm::mat3 turn(float radians) {
  return glm::mat3(glm::rotate(glm::mat4(1.0f), radians, glm::vec3(0, 1, 0)));
}

// A square larger than the ortho view turns about the view axis and slides,
// under a rotation-plus-translation field that turns with it, for 50 frames
// on the GPU and in CPU references (each pixel's texture comes from where
// the last frame drew its point, moved back along the flow): `with_flow`
// the one told the flow's own displacement (the streaks' direction), the
// other not (its display follows the pixel's whole displacement). Positions
// and field are affine in the points, so the per-vertex interpolation is
// exact.
struct TurningSquare {
  ImageF texture, shown;  // the GPU's F_t and D(F_t)
  ReferenceIbfvs with_flow, without_flow;
};
TurningSquare turning_square(const RenderSettings& settings, float turn_per_frame) {
  const int w = settings.width, h = settings.height;
  const TriMesh square = make_square(2.5f, 30);
  const glm::vec3 slide(0.004f, -0.002f, 0.0f);
  const glm::vec3 omega(0, 0, 0.9f), u(0.15f, -0.05f, 0);
  const float dt = 0.012f;
  const auto place = [&](int k, const glm::vec3& m) {
    const float a = turn_per_frame * static_cast<float>(k);
    return glm::vec3(std::cos(a) * m.x - std::sin(a) * m.y, std::sin(a) * m.x + std::cos(a) * m.y,
                     0.0f) +
           static_cast<float>(k) * slide;
  };
  IbfvsRenderer r(settings);
  r.set_mesh(square, std::vector<glm::vec3>(square.vertex_count(), glm::vec3(0.0f)));
  TurningSquare out{{},
                    {},
                    ReferenceIbfvs(w, h, settings.background.x, settings.noise),
                    ReferenceIbfvs(w, h, settings.background.x, settings.noise)};
  for (ReferenceIbfvs* ref : {&out.with_flow, &out.without_flow}) {
    ref->set_filter_length(settings.filter_length);
    ref->set_sharpen(settings.sharpen);
    ref->set_compensated(settings.resample == Resample::Compensated);
  }
  for (int k = 0; k < 50; ++k) {
    std::vector<glm::vec3> positions(square.vertex_count()), field(square.vertex_count());
    for (std::size_t i = 0; i < positions.size(); ++i) {
      positions[i] = place(k, square.positions[i]);
      field[i] = glm::cross(omega, positions[i]) + u;
    }
    r.set_surface_steps(positions, square.normals, positions, square.normals);
    r.set_field_steps(field, field);
    r.render_frame(flat_view(), dt);
    BackwardMap map;
    map.width = w;
    map.height = h;
    map.covered.assign(static_cast<std::size_t>(w) * h, 1);
    map.source.resize(map.covered.size());
    map.flow.resize(map.covered.size());
    const float a = turn_per_frame * static_cast<float>(k);
    const glm::vec2 pixels(0.5f * w, 0.5f * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const glm::vec3 p(2.0f * (x + 0.5f) / w - 1.0f, 2.0f * (y + 0.5f) / h - 1.0f, 0.0f);
        // The point drawn here, where the last frame drew it (the first
        // frame has no last one), moved back along the flow.
        const glm::vec3 q = p - static_cast<float>(k) * slide;
        const glm::vec3 m(std::cos(a) * q.x + std::sin(a) * q.y,
                          -std::sin(a) * q.x + std::cos(a) * q.y, 0.0f);
        const glm::vec3 drawn = k == 0 ? p : place(k - 1, m);
        const glm::vec3 from = drawn - (glm::cross(omega, p) + u) * dt;
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        map.source[i] = (glm::vec2(from) + 1.0f) * pixels;
        map.flow[i] = glm::vec2(drawn - from) * pixels;
      }
    out.with_flow.step(map, k, settings.alpha);
    map.flow.clear();
    out.without_flow.step(map, k, settings.alpha);
  }
  out.texture = r.read_texture().select_channels(0, 1);
  out.shown = to_float_channel(r.read_output(), 0);
  return out;
}

TEST_F(RendererGLTest, EqualsTheCpuReferenceOnATurningSquare) {
  // 0.02 radians a frame: 1.9 pixels at the image corners.
  const TurningSquare t = turning_square(reference_settings(192, 160), 0.02f);
  const test::Difference d = test::difference(t.texture.pixels, t.with_flow.texture().pixels);
  std::printf("turning square, GPU vs CPU reference after 50 frames: max %.4f mean %.5f\n", d.max,
              d.mean);
  // Measured on llvmpipe: max 0.0030, mean 0.0015, as the still square's.
  EXPECT_LT(d.mean, 0.003);
  EXPECT_LT(d.max, 0.01);
}

TEST_F(RendererGLTest, TheDisplayFollowsTheFlowNotTheSurfacesMotion) {
  // The square turning 0.08 radians a frame (up to 8 pixels, against the
  // flow's 2.5) under the default look's warp, sharpening and display
  // filter: the GPU's picture is the reference's that follows the flow's
  // own direction, not the one that follows each pixel's whole
  // displacement (the surface's jump smeared along the display).
  RenderSettings settings = reference_settings(192, 160);
  settings.beta = 1.0f;  // F is the displayed texture
  settings.filter_length = 8.0f;
  settings.sharpen = 2.0f;
  settings.resample = Resample::Compensated;
  const TurningSquare t = turning_square(settings, 0.08f);
  const test::Difference texture = test::difference(t.texture.pixels, t.with_flow.texture().pixels);
  const test::Difference flow = test::difference(t.shown.pixels, t.with_flow.shown().pixels);
  const test::Difference motion = test::difference(t.shown.pixels, t.without_flow.shown().pixels);
  std::printf(
      "turning square, the default look's display: GPU vs CPU F_t mean %.5f; shown mean %.5f "
      "(%.3f%% above 0.02), against the display along the whole displacement %.5f (%.2f%%)\n",
      texture.mean, flow.mean, 100.0 * flow.above, motion.mean, 100.0 * motion.above);
  // Measured on llvmpipe: 0.0013; 0.0022 (0.75%: sharpening magnifies
  // rounding, 0.5-0.9% whatever the turn), against 0.019 (30%). Before the
  // display took the flow's own direction, the GPU drew the latter.
  EXPECT_LT(texture.mean, 0.004);
  EXPECT_LT(flow.mean, 0.004);
  EXPECT_LT(flow.above, 0.015);
  EXPECT_GT(motion.mean, 5.0 * flow.mean);
}

// The default look's settings for a w x h image.
RenderSettings default_look(int w, int h) {
  ibfvs::Scene s;
  s.width = w;
  s.height = h;
  return prepare_scene(s, make_torus(1.0f, 0.4f, 32, 16), "torus").settings;
}

// The texture of `frames` frames of a sphere seen by a camera orbiting it
// (`orbit`), or turning the other way under a still camera (its points,
// normals and field turned: with `field_lag` 1 the field as it was one
// frame earlier), or the same points as another mesh each frame (`replace`:
// without the body's motion).
struct Turned {
  std::vector<float> texture, shown;
  std::vector<std::uint8_t> mask;
};
enum class Way { Orbit, Turn, Replace };
Turned turned_sphere(Way way, int field_lag) {
  constexpr int w = 200, h = 160;
  const Scene sphere = sphere_scene("rotate:0,0,1", TangentMode::Project, float(w) / h);
  const glm::mat4 v0 = sphere.camera.view(), projection = sphere.camera.projection();
  constexpr float per_frame = glm::radians(1.5f);
  IbfvsRenderer r(default_look(w, h));
  r.set_mesh(sphere.mesh, sphere.field);
  const std::size_t n = sphere.mesh.vertex_count();
  for (int k = 0; k < 60; ++k) {
    const glm::mat3 m = turn(-per_frame * static_cast<float>(k));
    if (way == Way::Orbit) {
      r.render_frame({v0 * glm::mat4(m), projection}, 1.0f);
      continue;
    }
    TriMesh moved = sphere.mesh;
    std::vector<glm::vec3> field(n);
    const glm::mat3 f = turn(-per_frame * static_cast<float>(std::max(k - field_lag, 0)));
    for (std::size_t i = 0; i < n; ++i) {
      moved.positions[i] = m * sphere.mesh.positions[i];
      moved.normals[i] = m * sphere.mesh.normals[i];
      field[i] = f * sphere.field[i];
    }
    if (way == Way::Turn) {
      r.set_surface_steps(moved.positions, moved.normals, moved.positions, moved.normals);
      r.set_field_steps(field, field);
    } else {
      r.replace_mesh(moved, field);
    }
    r.render_frame({v0, projection}, 1.0f);
  }
  return {grey(r.read_texture()), grey(r.read_output()), r.read_coverage()};
}

TEST_F(RendererGLTest, ABodyTurningEqualsTheCameraTurningAroundIt) {
  // The same picture two ways, at the default look: the camera orbits a
  // still sphere, or the sphere turns the other way under a still camera.
  // The two differ only in the field's direction at the source: the orbit
  // takes it as it was one frame earlier, the turning body as it is now
  // (1.5 degrees apart); with the field one frame late the two are equal.
  const Turned orbit = turned_sphere(Way::Orbit, 0);
  const Turned late = turned_sphere(Way::Turn, 1);
  const Turned turning = turned_sphere(Way::Turn, 0);
  const Turned replaced = turned_sphere(Way::Replace, 0);
  const std::vector<std::uint8_t>& mask = orbit.mask;
  EXPECT_EQ(turning.mask, mask);
  const double equal = correlation(orbit.texture, late.texture, mask, mask);
  const double same = correlation(orbit.texture, turning.texture, mask, mask);
  const double shown = correlation(orbit.shown, turning.shown, mask, mask);
  const double shown_late = correlation(orbit.shown, late.shown, mask, mask);
  const double control = correlation(orbit.texture, replaced.texture, mask, mask);
  const test::Difference d = test::difference(orbit.texture, late.texture, 0.01);
  std::printf(
      "body turning vs camera turning: F_t correlation %.5f with the field one frame late "
      "(max difference %.4f, F %.5f), %.4f turning with the body (F %.4f); without the body's "
      "motion %.4f\n",
      equal, d.max, shown_late, same, shown, control);
  // Measured on llvmpipe: 1.00000 (max 0.0005, F 1.0000); 0.977 (F 0.901:
  // the display follows the flow, 1.5 degrees apart); 0.48.
  EXPECT_GT(equal, 0.9999);
  EXPECT_LT(d.max, 0.01);
  EXPECT_GT(shown_late, 0.999);
  EXPECT_GT(same, 0.95);
  EXPECT_GT(shown, 0.85);
  EXPECT_LT(control, 0.6);
}

TEST_F(RendererGLTest, AnotherMeshKeepsTheTextureInTheImage) {
  // A change of topology (the sphere tessellated again, finer) takes the
  // texture on from the image: the picture right after the change is the
  // one before it, advanced one frame; set_mesh starts from noise.
  constexpr int w = 160, h = 128;
  const Scene coarse = sphere_scene("rotate:0,0,1", TangentMode::Project, float(w) / h);
  TriMesh fine = make_sphere(1.0f, 130, 260, 0.06f);
  const std::vector<glm::vec3> fine_field =
      evaluate_field(fine, FieldSpec::parse("rotate:0,0,1"), TangentMode::Project);
  const RenderSettings settings = default_look(w, h);
  const ViewState view{coarse.camera.view(), coarse.camera.projection()};
  IbfvsRenderer kept(settings), restarted(settings);
  kept.set_mesh(coarse.mesh, coarse.field);
  restarted.set_mesh(coarse.mesh, coarse.field);
  for (int k = 0; k < 40; ++k) {
    kept.render_frame(view, 1.0f);
    restarted.render_frame(view, 1.0f);
  }
  const std::vector<float> before = grey(kept.read_texture());
  const std::vector<std::uint8_t> mask = kept.read_coverage();
  kept.replace_mesh(fine, fine_field);
  restarted.set_mesh(fine, fine_field);
  kept.render_frame(view, 1.0f);
  restarted.render_frame(view, 1.0f);
  const double carried = correlation(before, grey(kept.read_texture()), mask, kept.read_coverage());
  const double fresh =
      correlation(before, grey(restarted.read_texture()), mask, restarted.read_coverage());
  std::printf("another mesh: correlation with the frame before %.3f (set_mesh: %.3f)\n", carried,
              fresh);
  EXPECT_GT(carried, 0.8);
  EXPECT_LT(std::abs(fresh), 0.2);
}

// ------------------------------------------------------------ the session

ibfvs::Scene torus_scene(int w, int h) {
  ibfvs::Scene s;
  s.mesh = "torus";
  s.width = w;
  s.height = h;
  apply_setting(s, "camera", "20,40,0");
  return s;
}

TEST_F(RendererGLTest, AChangeOfDataToTheSameContentLeavesThePictureAsItWas) {
  const PreparedScene prepared = prepare_scene(torus_scene(120, 96));
  Session changed(prepared), unchanged(prepared);
  for (int k = 0; k < 30; ++k) {
    changed.advance();
    unchanged.advance();
  }
  // The same surface and field again, as a host hands them over (its own
  // vertex order: the prepared mesh's inverse order), and the mesh as given.
  TriMesh given = make_torus(1.0f, 0.4f, 160, 64);
  changed.change_data(prepare_change(changed.scene(), given, "the input"));
  changed.advance();
  unchanged.advance();
  EXPECT_EQ(changed.read_output().pixels, unchanged.read_output().pixels);
  EXPECT_EQ(changed.renderer().read_texture().pixels, unchanged.renderer().read_texture().pixels);
}

TEST_F(RendererGLTest, ChangedDataGoesOnFromTheTexture) {
  // New vectors on moved points (the torus shifted a little): the texture
  // goes on, the picture after the change correlates with the one before
  // far more than a new session's does.
  const PreparedScene prepared = prepare_scene(torus_scene(120, 96));
  Session session(prepared);
  for (int k = 0; k < 30; ++k) session.advance();
  const std::vector<float> before = grey(session.read_output());
  const std::vector<std::uint8_t> mask = session.renderer().read_coverage();
  TriMesh given = make_torus(1.0f, 0.4f, 160, 64);
  for (glm::vec3& p : given.positions) p += glm::vec3(0.01f, 0.0f, 0.0f);
  PreparedScene next = prepare_change(session.scene(), given, "the input");
  EXPECT_EQ(next.mesh->triangles, prepared.mesh->triangles);  // the same order, moved
  Session unchanged(prepared);
  for (int k = 0; k < 34; ++k) unchanged.advance();
  session.change_data(std::move(next));
  for (int k = 0; k < 4; ++k) session.render(session.camera());
  EXPECT_TRUE(session.renderer().moving());
  const auto with_before = [&](const Session& s) {
    return correlation(before, grey(s.read_output()), mask, s.renderer().read_coverage());
  };
  Session fresh(prepare_change(prepared, given, "the input"));
  for (int k = 0; k < 4; ++k) fresh.advance();
  const double kept = with_before(session), still = with_before(unchanged),
               afresh = with_before(fresh);
  std::printf(
      "changed data, 4 frames after it: correlation with the frame before %.3f (the "
      "data unchanged %.3f, a new session %.3f)\n",
      kept, still, afresh);
  EXPECT_GT(kept, 0.85 * still);
  EXPECT_LT(afresh, 0.3);
}

TEST_F(RendererGLTest, AResizeCarriesTheTexture) {
  Session session(prepare_scene(torus_scene(160, 128)));
  for (int k = 0; k < 30; ++k) session.advance();
  session.resize(320, 256);
  session.advance();
  const std::vector<float> big = grey(session.renderer().read_texture());
  const std::vector<std::uint8_t> big_mask = session.renderer().read_coverage();
  // Against the same run in one size: the picture is the other size's
  // scaled up, not fresh noise.
  Session reference(prepare_scene(torus_scene(160, 128)));
  for (int k = 0; k < 31; ++k) reference.advance();
  const ImageF small = reference.renderer().read_texture();
  const std::vector<std::uint8_t> small_mask = reference.renderer().read_coverage();
  // The bigger picture's 2 x 2 blocks: the new size's finer noise averaged out.
  std::vector<float> down(small_mask.size());
  std::vector<std::uint8_t> down_mask(small_mask.size());
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 160; ++x) {
      float sum = 0.0f;
      std::uint8_t all = 1;
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const std::size_t k = static_cast<std::size_t>(2 * y + j) * 320 + 2 * x + i;
          sum += big[k];
          all = all && big_mask[k];
        }
      down[y * 160 + x] = 0.25f * sum;
      down_mask[y * 160 + x] = all;
    }
  const double carried = correlation(down, grey(small), down_mask, small_mask);
  // The control: the texture restarted at the new size.
  session.restart();
  session.advance();
  std::vector<float> restarted(down.size());
  const ImageF again = session.renderer().read_texture();
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 160; ++x)
      restarted[y * 160 + x] =
          0.25f * (again.at(2 * x, 2 * y) + again.at(2 * x + 1, 2 * y) +
                   again.at(2 * x, 2 * y + 1) + again.at(2 * x + 1, 2 * y + 1));
  const double fresh = correlation(restarted, grey(small), down_mask, small_mask);
  std::printf(
      "resize 160x128 -> 320x256: correlation with the unresized run %.3f (restarted "
      "%.3f)\n",
      carried, fresh);
  // Measured on llvmpipe: 0.68 (restarted 0.01): the new size's first
  // frame adds its own finer noise.
  EXPECT_GT(carried, 0.5);
  EXPECT_LT(std::abs(fresh), 0.2);
  EXPECT_EQ(session.scene().width, 320);
}

TEST_F(RendererGLTest, ASeriesWhosePointsMoveIsDrawnOnEachStepsPoints) {
  // A square turning 10 degrees a step about the view axis, one frame a
  // step: each frame covers the pixels of its own step's square, not the
  // first step's.
  const test::TempDir dir;
  for (int k = 0; k < 4; ++k) {
    TriMesh m = make_square(0.8f, 8);
    const glm::mat3 r = glm::mat3(
        glm::rotate(glm::mat4(1.0f), glm::radians(10.0f * static_cast<float>(k)), {0, 0, 1}));
    for (glm::vec3& p : m.positions) p = r * p;
    compute_vertex_normals(m);
    m.vectors.resize(m.vertex_count());
    for (std::size_t i = 0; i < m.vertex_count(); ++i)
      m.vectors[i] = glm::vec3(-m.positions[i].y, m.positions[i].x, 0.0f);
    write_ply(m, dir / ("turn_" + std::to_string(k) + ".ply"));
  }
  ibfvs::Scene s;
  s.mesh = (dir / "turn_*.ply").string();
  s.width = 128;
  s.height = 128;
  s.frames_per_step = 1;
  const PreparedScene prepared = prepare_scene(s);
  Session session(prepared);
  const ViewState view{session.camera().view(), session.camera().projection()};
  for (int k = 0; k < 4; ++k) {
    session.advance();
    const TriMesh step = read_mesh(dir / ("turn_" + std::to_string(k) + ".ply"));
    IbfvsRenderer alone(prepared.settings);
    alone.set_mesh(step, std::vector<glm::vec3>(step.vertex_count(), glm::vec3(0.0f)));
    alone.render_frame(view, 1.0f);
    const std::vector<std::uint8_t> expected = alone.read_coverage();
    const std::vector<std::uint8_t> drawn = session.renderer().read_coverage();
    std::size_t differ = 0;
    for (std::size_t i = 0; i < drawn.size(); ++i) differ += drawn[i] != expected[i];
    EXPECT_LT(differ, 8u) << "step " << k;  // the edge pixels, rounded alike or not
  }
}

}  // namespace
}  // namespace ibfvs::rendertest
