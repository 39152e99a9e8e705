// The session: the same frames as the renderer driven by hand, the run's own
// stepping (lock, lock camera, orbit), and drawing inside a context whose
// state belongs to somebody else (a host such as ParaView).

#include <epoxy/gl.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gl_fixture.h"
#include "ibfvs/core/geometry/displacement.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/objects.h"
#include "ibfvs/render/ibfvs_renderer.h"
#include "ibfvs/render/session.h"

namespace ibfvs {
namespace {

class SessionGLTest : public test::GlTest {};

// The frames of each render as hosts render (no GL): `renders` renders of
// each of `steps` data, the first data rendered `first` times.
std::vector<int> paced(int frames_per_step, int first, int renders, int steps) {
  FramePacer pacer(frames_per_step);
  std::vector<int> out;
  for (int k = 0; k < first; ++k) out.push_back(pacer.next(k == 0, k == 0));
  for (int step = 1; step < steps; ++step)
    for (int k = 0; k < renders; ++k) out.push_back(pacer.next(k == 0, false));
  return out;
}

TEST(FramePacer, EveryStepGetsItsFramesAndPlayNoJump) {
  // Save Animation: a step rendered once gets all three at its own data,
  // the second step too though ParaView rendered the first three times.
  EXPECT_EQ(paced(3, 3, 1, 4), (std::vector<int>{3, 1, 1, 3, 3, 3}));
  // Save Animation started at another step: ParaView renders the first
  // step it saves twice; the next one still gets all three.
  {
    FramePacer pacer(3);
    std::vector<int> frames;
    for (int k = 0; k < 40; ++k) frames.push_back(pacer.next(k < 2, k == 0));  // at step 5
    for (int step = 0; step < 3; ++step)
      for (int k = 0; k < (step == 0 ? 2 : 1); ++k) frames.push_back(pacer.next(k == 0, false));
    EXPECT_EQ(std::vector<int>(frames.end() - 4, frames.end()), (std::vector<int>{1, 1, 3, 3}));
  }
  // Sequence mode, three renders a step: the change owes the frames the
  // last step's renders fell short of, none; four: none; two count as one.
  EXPECT_EQ(paced(3, 1, 3, 3), (std::vector<int>{3, 3, 1, 1, 1, 1, 1}));
  EXPECT_EQ(paced(3, 1, 4, 3), (std::vector<int>{3, 3, 1, 1, 1, 1, 1, 1, 1}));
  EXPECT_EQ(paced(5, 1, 4, 3), (std::vector<int>{5, 5, 1, 1, 1, 2, 1, 1, 1}));
  EXPECT_EQ(paced(3, 1, 2, 3), (std::vector<int>{3, 3, 1, 3, 1}));
  // Play (many renders a step) and a steady view: one a render; where the
  // step moved the surface, all three.
  EXPECT_EQ(paced(3, 30, 30, 3)[30 + 30], 1);
  {
    FramePacer pacer(3);
    for (int k = 0; k < 30; ++k) pacer.next(k < 2, k == 0);
    EXPECT_EQ(pacer.next(true, false, true), 3);
    EXPECT_EQ(pacer.next(false, false, false), 1);
  }
  // A change that moves a surface carrying its texture (a turning part):
  // its renders count as they are, the first data's too. Play in pvbatch
  // (many renders a step): one frame at every change, the first too; the
  // GUI's Play (two a step): two; Save Animation (one a step): all three.
  {
    FramePacer play(3), gui(3), save(3);
    std::vector<int> frames;
    for (int k = 0; k < 30; ++k) play.next(k == 0, k == 0);
    for (int step = 1; step < 3; ++step)
      for (int k = 0; k < 30; ++k) frames.push_back(play.next(k == 0, false, false, k == 0));
    EXPECT_EQ(frames[0], 1);
    EXPECT_EQ(frames[30], 1);
    frames.clear();
    for (int step = 0; step < 3; ++step)
      for (int k = 0; k < 2; ++k)
        frames.push_back(gui.next(k == 0, step == 0 && k == 0, false, step > 0 && k == 0));
    EXPECT_EQ(frames, (std::vector<int>{3, 1, 2, 1, 2, 1}));
    frames.clear();
    for (int step = 0; step < 4; ++step)
      frames.push_back(save.next(true, step == 0, false, step > 0));
    EXPECT_EQ(frames, (std::vector<int>{3, 3, 3, 3}));
  }
  // A TemporalInterpolator: every render a change, each the same.
  EXPECT_EQ(paced(4, 1, 1, 5), (std::vector<int>{4, 4, 4, 4, 4}));
  // A restart forms a new texture; the data it starts on counts once.
  FramePacer pacer(3);
  for (int k = 0; k < 10; ++k) pacer.next(false, false);
  EXPECT_EQ(pacer.next(true, true), 3);
  for (int k = 0; k < 10; ++k) pacer.next(false, false);
  EXPECT_EQ(pacer.next(true, false), 3);
  // Clamped.
  pacer.set_frames_per_step(0);
  EXPECT_EQ(pacer.frames_per_step(), 1);
  pacer.set_frames_per_step(100000);
  EXPECT_EQ(pacer.frames_per_step(), kMaxFramesPerStep);
}

Scene small_scene() {
  Scene s;
  s.mesh = "torus";
  s.width = 96;
  s.height = 80;
  s.orbit = 2.0f;
  apply_setting(s, "camera", "20,40,0");
  return s;
}

TEST_F(SessionGLTest, FramesEqualTheRendererDrivenByHand) {
  const PreparedScene prepared = prepare_scene(small_scene());
  Session session(prepared);
  IbfvsRenderer by_hand(prepared.settings);
  by_hand.set_mesh(*prepared.mesh, prepared.field);
  Camera camera(mesh_bounds(*prepared.mesh), prepared.camera, 96.0f / 80.0f);
  for (int k = 0; k < 12; ++k) {
    session.advance();
    if (k > 0) camera.orbit(2.0f);
    by_hand.render_frame({camera.view(), camera.projection()}, prepared.dt);
  }
  EXPECT_EQ(session.frame(), 12);
  EXPECT_EQ(session.read_output().pixels, by_hand.read_output().pixels);
}

TEST_F(SessionGLTest, LocksAtItsFrameAndMovesToTheLockCamera) {
  Scene s = small_scene();
  s.orbit = 0.0f;
  s.lock_at = 5;
  s.lock_camera = glm::vec3(60.0f, 10.0f, 0.0f);
  Session session(prepare_scene(s));
  for (int k = 0; k < 5; ++k) session.advance();
  EXPECT_FALSE(session.renderer().locked());
  const ImageF before = session.renderer().read_texture();
  session.advance();
  EXPECT_TRUE(session.renderer().locked());
  EXPECT_EQ(session.camera().params().azimuth_deg, 60.0f);
  for (int k = 0; k < 3; ++k) session.advance();
  // Locked: F_t no longer changes.
  EXPECT_EQ(session.renderer().read_texture().pixels, before.pixels);
}

// Session::set, the one set of rules every front end follows: what the
// running animation takes (the texture going on), and the scene prepared
// again in the session where a key needs it.
TEST_F(SessionGLTest, SettingsChangeOnTheRunningAnimationByTheKeysRules) {
  Session session(prepare_scene(small_scene()));
  for (int k = 0; k < 6; ++k) session.advance();
  const ImageF texture = session.renderer().read_texture();
  const auto changed = [&](const char* key, const char* value) {
    Scene next = session.scene().scene;
    apply_setting(next, key, value);
    return session.set(next);
  };
  // Texture settings: the next frame takes them; the texture is as it was.
  ASSERT_EQ(changed("alpha", "0.3"), SetResult::Applied);
  ASSERT_EQ(changed("filter", "8"), SetResult::Applied);
  EXPECT_EQ(session.renderer().settings().alpha, 0.3f);
  EXPECT_EQ(session.renderer().settings().filter_length, 8.0f);
  EXPECT_EQ(session.renderer().read_texture().pixels, texture.pixels);
  EXPECT_EQ(session.frame(), 6);
  // The step: dt follows it.
  const float dt = session.dt();
  ASSERT_EQ(changed("step", std::to_string(2.0f * session.scene().scene.step).c_str()),
            SetResult::Applied);
  EXPECT_FLOAT_EQ(session.dt(), 2.0f * dt);
  // A new noise grid: the texture goes on.
  ASSERT_EQ(changed("scale", "3"), SetResult::Applied);
  EXPECT_EQ(session.renderer().settings().noise.scale, 3.0f);
  EXPECT_EQ(session.renderer().read_texture().pixels, texture.pixels);
  // The camera: the view moves, dt is the step's for it.
  ASSERT_EQ(changed("camera", "60,10,0"), SetResult::NewView);
  EXPECT_EQ(session.camera().params().azimuth_deg, 60.0f);
  EXPECT_GT(session.dt(), 0.0f);
  EXPECT_NE(session.dt(), 2.0f * dt);
  // A new size: the texture resampled to it.
  ASSERT_EQ(changed("size", "64x48"), SetResult::NewView);
  EXPECT_EQ(session.renderer().read_texture().width, 64);
  EXPECT_EQ(session.renderer().read_texture().height, 48);
  EXPECT_EQ(session.frame(), 6);
  // A new seed: the texture starts afresh.
  ASSERT_EQ(changed("seed", "7"), SetResult::Applied);
  EXPECT_EQ(session.frame(), 0);
  // A key that needs the scene prepared again: the session prepares it,
  // and over the same points the texture goes on from where it is.
  for (int k = 0; k < 4; ++k) session.advance();
  const ImageF before = session.read_texture();
  EXPECT_EQ(changed("color_by", "speed"), SetResult::Prepared);
  EXPECT_EQ(session.scene().scene.color_by, "speed");
  EXPECT_TRUE(session.settings().use_color);
  EXPECT_EQ(session.frame(), 4);
  EXPECT_EQ(session.read_texture().pixels, before.pixels);
  // Over other points (a subdivided mesh) it starts afresh.
  EXPECT_EQ(changed("subdivide", "1"), SetResult::Prepared);
  EXPECT_EQ(session.frame(), 0);
  EXPECT_GT(session.scene().mesh->vertex_count(),
            prepare_scene(small_scene()).mesh->vertex_count());
  // Values that are not valid, and data that cannot be prepared: nothing
  // changes.
  EXPECT_THROW(changed("mesh", "/no/such/mesh.ply"), InputError);
  EXPECT_EQ(session.scene().scene.subdivide, 1);
  Scene bad = session.scene().scene;
  bad.alpha = 1.5f;
  EXPECT_THROW(session.set(bad), SettingError);
  EXPECT_EQ(session.renderer().settings().alpha, 0.3f);
  EXPECT_EQ(session.scene().scene.alpha, 0.3f);
  // Keys read only by a front end change nothing on the texture.
  EXPECT_EQ(changed("frames", "99"), SetResult::Applied);
}

// A host's change is taken when it is made (checked, planned, dt refitted)
// and drawn with its context: the GPU's part waits for the next frame.
TEST_F(SessionGLTest, AHostsChangeIsTakenNowAndDrawnAtTheNextFrame) {
  Session session(prepare_scene(small_scene()));
  for (int k = 0; k < 3; ++k) session.advance();
  const float dt = session.dt();
  Scene next = session.scene().scene;
  next.alpha = 0.3f;
  next.scale = 5.0f;
  next.step = 2.0f * next.step;
  ASSERT_EQ(session.set(next, nullptr, Apply::AtNextFrame), SetResult::Applied);
  EXPECT_EQ(session.scene().settings.noise.scale, 5.0f);
  EXPECT_FLOAT_EQ(session.dt(), 2.0f * dt);
  EXPECT_NE(session.settings().alpha, 0.3f);  // the renderer: at the next frame
  Scene bad = next;
  bad.beta = 3.0f;
  EXPECT_THROW(session.set(bad, nullptr, Apply::AtNextFrame), SettingError);
  session.advance();
  EXPECT_EQ(session.settings().alpha, 0.3f);
  EXPECT_EQ(session.settings().noise.scale, 5.0f);
  EXPECT_EQ(session.frame(), 4);  // a new grid: the texture went on
  // A key that needs preparing: prepared now, drawn over the same surface.
  next.color_by = "speed";
  ASSERT_EQ(session.set(next, nullptr, Apply::AtNextFrame), SetResult::Prepared);
  EXPECT_EQ(session.scene().scene.color_by, "speed");
  EXPECT_FALSE(session.settings().use_color);
  session.advance();
  EXPECT_TRUE(session.settings().use_color);
  EXPECT_EQ(session.frame(), 5);
}

// A new step fits dt from the speed the preparation found: a series' steps
// are not read again (the viewer's step slider, a host's Step), nor is the
// prepared scene copied; a new field fits it again.
TEST_F(SessionGLTest, ANewStepReadsNoStepOfASeries) {
  PreparedScene p = prepare_scene(small_scene());
  int reads = 0;
  const std::vector<glm::vec3> field = p.field;
  p.step_count = 3;
  p.step_data = [&reads, field](std::size_t) {
    ++reads;
    StepData d;
    d.field = field;
    return d;
  };
  Session session(std::move(p));
  session.advance();
  const int read = reads;
  const float dt = session.dt();
  Scene next = session.scene().scene;
  for (int k = 1; k <= 5; ++k) {
    next.step = static_cast<float>(k);
    ASSERT_EQ(session.set(next), SetResult::Applied);
    EXPECT_FLOAT_EQ(session.dt(), dt * static_cast<float>(k) / small_scene().step);
  }
  EXPECT_EQ(reads, read);
  std::vector<glm::vec3> faster = field;
  for (glm::vec3& v : faster) v *= 2.0f;
  session.set_field(faster);
  EXPECT_FLOAT_EQ(session.dt(), 0.5f * dt * 5.0f / small_scene().step);
}

// What a front end reads goes to the renderer in force: a restart, a new
// size or noise grid and a scene prepared again each make a new one (a
// reference to the old one held across them, as `ibfvs render` once held,
// would be left dangling).
TEST_F(SessionGLTest, ReadsFollowTheRendererInForce) {
  Session session(prepare_scene(small_scene()));
  for (int k = 0; k < 3; ++k) session.advance();
  session.resize(48, 40);
  EXPECT_EQ(session.read_output().width, 48);
  EXPECT_EQ(session.read_texture().height, 40);
  EXPECT_EQ(session.read_depth().width, 48);
  Scene next = session.scene().scene;
  next.scale = 4.0f;
  ASSERT_EQ(session.set(next), SetResult::Applied);
  EXPECT_EQ(session.settings().noise.scale, 4.0f);
  session.restart();
  EXPECT_EQ(session.renderer_frame(), 0);
  session.advance();
  EXPECT_EQ(session.renderer_frame(), 1);
  EXPECT_EQ(session.read_output().height, 40);
  session.finish();
}

// The one restart (the viewer's button, Python's restart(), a host's):
// the scene's initial state, frame 0, unlocked; the settings in force, the
// time of a series and dt stay.
TEST_F(SessionGLTest, OneRestartStartsFromTheScenesInitialState) {
  Scene s = small_scene();
  s.init = InitMode::RandomCells;
  Session fresh(prepare_scene(s));
  const ImageF initial = fresh.renderer().read_texture();
  Session session(prepare_scene(s));
  Scene next = session.scene().scene;
  next.alpha = 0.2f;
  ASSERT_EQ(session.set(next), SetResult::Applied);
  const float dt = session.dt();
  for (int k = 0; k < 5; ++k) session.advance();
  session.lock();
  ASSERT_NE(session.renderer().read_texture().pixels, initial.pixels);
  session.restart();
  EXPECT_EQ(session.frame(), 0);
  EXPECT_EQ(session.renderer().frame(), 0);
  EXPECT_FALSE(session.locked());
  EXPECT_EQ(session.renderer().read_texture().pixels, initial.pixels);  // the cells again
  EXPECT_EQ(session.renderer().settings().alpha, 0.2f);
  EXPECT_EQ(session.dt(), dt);
}

// dt by the one rule for the view it is drawn with: the scene's camera, a
// host's camera (the viewer's zoom), a host's world units per pixel.
TEST_F(SessionGLTest, DtFitsTheStepInTheViewItIsDrawnWith) {
  Session session(prepare_scene(small_scene()));
  const float own = session.dt();
  ASSERT_GT(own, 0.0f);
  const Bounds bounds = mesh_bounds(*session.scene().mesh);
  CameraParams params = session.camera().params();
  params.distance = 0.5f * session.camera().distance_world() / bounds.diagonal();
  const Camera near_camera(bounds, params, 96.0f / 80.0f);
  session.fit_dt(near_camera);  // nearer: the step spans less world
  EXPECT_GT(session.dt(), 0.25f * own);
  EXPECT_LT(session.dt(), 0.7f * own);
  const float near = session.dt();
  Scene next = session.scene().scene;
  next.step = 2.0f * next.step;  // a new step keeps the host's camera
  ASSERT_EQ(session.set(next), SetResult::Applied);
  EXPECT_FLOAT_EQ(session.dt(), 2.0f * near);
  // A host's world units per pixel: the fastest vector moves `step` pixels
  // at its focal point (normalised in image space, the default, every
  // point does whatever dt is: > 0 where anything moves).
  ASSERT_TRUE(session.scene().scene.image_normalize);
  session.follow_host(0.01, 2.0f);
  EXPECT_FLOAT_EQ(session.dt(), dt_for_step(session.scene().scene.step, 2.0f, 0.01));
  session.follow_host(0.01, 0.0f);
  EXPECT_EQ(session.dt(), 0.0f);
  // The scene's own dt wins over every view.
  Scene own_dt = small_scene();
  own_dt.image_normalize = false;
  own_dt.dt = 0.125f;
  Session fixed(prepare_scene(own_dt));
  fixed.fit_dt(near_camera);
  EXPECT_EQ(fixed.dt(), 0.125f);
  fixed.follow_host(0.01, 2.0f);
  EXPECT_EQ(fixed.dt(), 0.125f);
}

TEST_F(SessionGLTest, LeavesTheHostsGlStateAsItFoundIt) {
  // The host's own framebuffer, viewport, program-free state and depth test.
  gl::Texture2D colour(32, 16, gl::Format::RGBA8, false);
  gl::Framebuffer host = gl::Framebuffer::create();
  host.attach_color(0, colour);
  host.finish(1);
  host.bind();
  glViewport(3, 4, 20, 10);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  host.clear_color(0, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  GLint before_fb = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &before_fb);

  Session session(prepare_scene(small_scene()));  // uploads: state saved too
  for (int k = 0; k < 3; ++k) session.advance();

  GLint fb = 0, read_fb = 0, viewport[4] = {};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fb);
  glGetIntegerv(GL_VIEWPORT, viewport);
  EXPECT_EQ(fb, before_fb);
  EXPECT_EQ(read_fb, before_fb);
  EXPECT_EQ(viewport[0], 3);
  EXPECT_EQ(viewport[1], 4);
  EXPECT_EQ(viewport[2], 20);
  EXPECT_EQ(viewport[3], 10);
  EXPECT_TRUE(glIsEnabled(GL_DEPTH_TEST));
  EXPECT_FALSE(glIsEnabled(GL_CULL_FACE));
  // The host's picture is untouched.
  std::vector<std::uint8_t> pixel(4);
  glReadPixels(5, 5, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel.data());
  EXPECT_EQ(pixel, (std::vector<std::uint8_t>{255, 0, 0, 255}));
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // And the session's own picture is there: the torus, not only background.
  const ImageU8 out = session.read_output();
  std::size_t surface = 0;
  for (std::size_t i = 0; i < out.pixels.size(); i += 4)
    surface += out.pixels[i] != out.pixels[0] || out.pixels[i + 1] != out.pixels[1];
  EXPECT_GT(surface, 500u);
}

}  // namespace
}  // namespace ibfvs
