// `ibfvs view`: the real window under Xvfb, driven by a script, and the
// viewer's logic without a window.

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include "command_runner.h"
#include "helpers.h"
#include "ibfvs/core/image/image.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/support/error.h"

#include "ibfvs/core/scene/scene.h"
#include "ibfvs/render_command.h"
#include "ibfvs/script_runner.h"
#include "ibfvs/viewer_state.h"

namespace ibfvs {
namespace {

// Runs `ibfvs view ARGS --script session.txt` in a virtual X server.
class ViewCommand : public test::CommandTest {
 protected:
  static bool have_xvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }
  test::Result view_under_xvfb(const std::string& args, const std::string& script) {
    file("session.txt", script);
    return run("view " + args + " --script session.txt", "xvfb-run -a -s '-screen 0 640x480x24'");
  }
};
using test::Result;

// Mean absolute difference of two RGB(A) images, 0..1.
double mean_difference(const ImageU8& a, const ImageU8& b) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  double sum = 0;
  const std::size_t n = std::min(a.pixels.size(), b.pixels.size());
  for (std::size_t i = 0; i < n; ++i) sum += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
  return sum / (255.0 * static_cast<double>(std::max<std::size_t>(n, 1)));
}

// The texture F_t recovered from two frames that differ only in beta
// (F = beta F_t + (1 - beta) F_s, eq. 11): with beta 0.5 and 0,
// F_t = 2 a - b. Its standard deviation over the surface (where b is not the
// grey background), in 0..1: near 0 for a blank texture.
double texture_spread(const ImageU8& a, const ImageU8& b) {
  double sum = 0, sum2 = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i + 2 < b.pixels.size(); i += b.channels) {
    if (std::abs(int(b.pixels[i]) - 128) + std::abs(int(b.pixels[i + 1]) - 128) < 4) continue;
    const double f = (2.0 * a.pixels[i] - b.pixels[i]) / 255.0;
    sum += f;
    sum2 += f * f;
    ++n;
  }
  if (n < 100) return 0.0;
  const double mean = sum / static_cast<double>(n);
  return std::sqrt(std::max(0.0, sum2 / static_cast<double>(n) - mean * mean));
}

TEST_F(ViewCommand, WithoutADisplayItSaysSoAndSuggestsRender) {
  const Result r = run("view --mesh torus", "env -u DISPLAY -u WAYLAND_DISPLAY");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err.rfind("ibfvs: error: no display", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("ibfvs render"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(ViewCommand, ScriptedSessionUnderXvfb) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run missing (Debian package xvfb)";
  const Result v = view_under_xvfb(
      "--mesh torus --camera 20,35,0 --size 160x128",
      "# the texture appears, beta matters, a saved scene re-renders, freezing holds\n"
      "30 screenshot a.png\n"
      "30 set beta 0\n"
      "31 screenshot b.png\n"
      "31 set beta 0.3\n"
      "40 save s.toml\n"
      "40 screenshot c.png\n"
      "40 texture t0.png\n"
      "40 mode freeze\n"
      "40 drag 80 0 10\n"
      "50 texture t1.png\n"
      "50 screenshot d.png\n"
      "51 quit\n");
  ASSERT_EQ(v.status, 0) << v.out << v.err;
  const ImageU8 a = read_png(dir_ / "a.png"), b = read_png(dir_ / "b.png");
  const ImageU8 c = read_png(dir_ / "c.png"), d = read_png(dir_ / "d.png");
  EXPECT_EQ(a.width, 160);
  EXPECT_EQ(a.height, 128);
  // The texture appears (beta 0.5) and goes with beta 0: fine detail drops.
  const double spread = texture_spread(a, b);
  std::printf("view: texture spread on the surface %.3f; beta 0.5 -> 0 changes the image by %.4f\n",
              spread, mean_difference(a, b));
  EXPECT_GT(spread, 0.08);
  EXPECT_GT(mean_difference(a, b), 0.01);
  // Freezing (section 3.7): F_t does not change while the camera turns.
  EXPECT_EQ(test::read_file(dir_ / "t0.png"), test::read_file(dir_ / "t1.png"));
  EXPECT_GT(mean_difference(c, d), 0.01);  // the view did turn
  // The saved scene, rendered headless, gives the viewer's frame.
  const Result r = run("render s.toml --out r.png -q");
  ASSERT_EQ(r.status, 0) << r.err << test::read_file(dir_ / "s.toml");
  const double diff = mean_difference(c, read_png(dir_ / "r.png"));
  std::printf("view: saved scene re-rendered by ibfvs render differs by %.5f (mean, 0..1)\n", diff);
  EXPECT_LT(diff, 0.005);
}

TEST_F(ViewCommand, ElementsStylesAndRecordingUnderXvfb) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run missing (Debian package xvfb)";
  const Result v = view_under_xvfb("--mesh torus --camera 0,40,0 --size 128x96",
                                   "2 record\n"
                                   "10 screenshot a.png\n"
                                   "10 element 0,-1,0,0,1,0,1.5,0.5,0\n"
                                   "20 screenshot b.png\n"
                                   "20 save el.toml\n"
                                   "20 style bronze\n"
                                   "30 screenshot c.png\n"
                                   "30 snapshot 200,150 big.png\n"
                                   "30 record\n"
                                   "31 quit\n");
  ASSERT_EQ(v.status, 0) << v.out << v.err;
  // The element replaced the rotation: the saved scene says so and renders.
  const std::string scene = test::read_file(dir_ / "el.toml");
  EXPECT_NE(scene.find("field = 'elements'"), std::string::npos) << scene;
  EXPECT_NE(scene.find("element = [ '0,-1,0,0,1,0,1.5,0.5,0' ]"), std::string::npos) << scene;
  const Result r = run("render el.toml --out el.png -q");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_GT(mean_difference(read_png(dir_ / "a.png"), read_png(dir_ / "b.png")), 0.01);
  // The bronze preset: warm colours on the surface.
  const ImageU8 c = read_png(dir_ / "c.png");
  double red = 0, blue = 0;
  for (std::size_t i = 0; i + 2 < c.pixels.size(); i += c.channels) {
    red += c.pixels[i];
    blue += c.pixels[i + 2];
  }
  EXPECT_GT(red, 1.1 * blue);
  // The offscreen render at another size.
  EXPECT_EQ(read_png(dir_ / "big.png").width, 200);
  EXPECT_EQ(read_png(dir_ / "big.png").height, 150);
  // The recording: one MP4 with the frames between the two toggles.
  EXPECT_GT(std::filesystem::file_size(dir_ / "ibfvs-view-0000.mp4"), 1000u);
}

TEST_F(ViewCommand, BadScriptsAndModesFailCleanly) {
  file("bad.txt", "5 dance\n");
  expect_error("view --mesh torus --script bad.txt", "bad.txt:1: unknown action 'dance'");
  file("args.txt", "5 zoom\n");
  expect_error("view --mesh torus --script args.txt", "'zoom' takes 1 argument(s), got 0");
  file("order.txt", "5 lock\n2 unlock\n");
  expect_error("view --mesh torus --script order.txt", "order.txt:2: frames must not decrease");
  expect_error("view --mesh torus --script missing.txt", "missing.txt: cannot open the script");
  expect_error("view --mesh torus --drag sideways", "--drag: expected plain");
}

TEST(ViewerCamera, RotateZoomPanReset) {
  const TriMesh m = make_torus(1.0f, 0.4f, 16, 8);
  app::ViewerCamera c(mesh_bounds(m), {}, 1.0f);
  c.rotate({100.0f, -50.0f});  // right and down: the camera goes left and up
  EXPECT_FLOAT_EQ(c.params().azimuth_deg, -30.0f);
  EXPECT_FLOAT_EQ(c.params().elevation_deg, 15.0f);
  c.rotate({0.0f, -1000.0f});
  EXPECT_FLOAT_EQ(c.params().elevation_deg, 89.0f);  // never over the pole
  const float before = c.camera().distance_world();
  c.zoom(1.0f);
  EXPECT_NEAR(c.camera().distance_world(), 0.9f * before, 1e-4f * before);
  // Panning moves the look-at point in the view plane by the pointer's motion.
  app::ViewerCamera p(mesh_bounds(m), {}, 1.0f);
  const glm::vec3 centre = mesh_bounds(m).centre();
  const glm::vec2 at = project_to_pixels(p.camera().view_projection(), centre, 200, 200);
  p.pan({10.0f, 0.0f}, 200);
  const glm::vec2 moved = project_to_pixels(p.camera().view_projection(), centre, 200, 200);
  EXPECT_NEAR(moved.x - at.x, 10.0f, 0.05f);
  EXPECT_NEAR(moved.y - at.y, 0.0f, 0.05f);
  p.reset();
  EXPECT_EQ(p.params().target, glm::vec3(0.0f));
  EXPECT_EQ(parse_enum<app::DragMode>("freeze"), app::DragMode::Freeze);
  EXPECT_EQ(enum_name(app::DragMode::Translate), "translate");
  EXPECT_THROW(parse_enum<app::DragMode>("spin"), InputError);
}

// `ibfvs view MESH`, the README's first viewer example, opens the mesh (the
// argument used to be refused), and at the default window size the panel
// leaves the mesh visible: the share of the mesh's pixels it hides is measured
// against the image without it.
TEST_F(ViewCommand, AMeshArgumentAndAPanelThatLeavesTheMeshVisible) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run missing";
  write_ply(make_torus(1.0f, 0.45f, 96, 48), dir_ / "ring.ply", true);
  const Result v =
      view_under_xvfb("ring.ply --camera 0,60,0", "5 screenshot a.png\n5 window w.png\n6 quit\n");
  ASSERT_EQ(v.status, 0) << v.err;
  const ImageU8 image = read_png(dir_ / "a.png"), window = read_png(dir_ / "w.png");
  ASSERT_EQ(image.width, 512);
  // Mesh pixels: grey texture, not the background. The panel's pixels are
  // bluish; whatever of the mesh it covers is missing from the window.
  // Only the image's part of the window counts (right of a side panel).
  const auto mesh_pixels = [&](const ImageU8& im) {
    std::size_t n = 0;
    for (std::size_t p = 0; p < static_cast<std::size_t>(im.width) * im.height; ++p) {
      if (static_cast<int>(p % im.width) < im.width - image.width) continue;
      const int r = im.pixels[p * im.channels], g = im.pixels[p * im.channels + 1],
                b = im.pixels[p * im.channels + 2];
      const bool background = std::abs(r - 128) + std::abs(g - 128) + std::abs(b - 128) < 4;
      n += !background && std::abs(r - g) <= 6 && std::abs(g - b) <= 6;
    }
    return n;
  };
  const std::size_t mesh = mesh_pixels(image), visible = mesh_pixels(window);
  const double hidden = 1.0 - static_cast<double>(visible) / static_cast<double>(mesh);
  std::printf("the panel hides %.1f%% of the mesh at 512x512 (window %dx%d)\n", 100.0 * hidden,
              window.width, window.height);
  EXPECT_GT(mesh, 40000u);
  EXPECT_LT(hidden, 0.02);
}

TEST(CommandLine, FlagsAreParsedOnceIntoTheTypedScene) {
  test::TempDir dir;
  test::write_file(dir / "s.toml", "mesh = \"torus\"\nalpha = 0.4\nstyle = \"bronze\"\n");
  CLI::App app;
  app::SceneOptions options;
  app::add_scene_options(app, options);
  app.parse(std::vector<std::string>{"-q", "0,0,0,0,1,0,1,0,0", "--element", "1,0,0,1,1,0,0,1,0",
                                     "--element", "0.25", "--alpha", "64x48", "--size", "--ortho",
                                     "0.3", "--beta", (dir / "s.toml").string()});
  const Scene s = app::scene_from_command_line(options);
  EXPECT_EQ(s.mesh, "torus");                // from the scene file
  EXPECT_EQ(s.alpha, 0.25f);                 // the flag overrides the file
  EXPECT_EQ(s.beta, 0.3f);                   // and the style under both
  EXPECT_EQ(s.color_map, ColorMap::Bronze);  // the style's own default
  EXPECT_EQ(s.width, 64);
  EXPECT_TRUE(s.camera.orthographic);
  EXPECT_TRUE(s.quiet);
  EXPECT_EQ(s.elements.size(), 2u);  // repeatable flags add up

  // A bad value: one line naming the flag.
  CLI::App bad;
  app::SceneOptions bad_options;
  app::add_scene_options(bad, bad_options);
  bad.parse(std::vector<std::string>{"p5,95", "--color-range"});
  try {
    app::scene_from_command_line(bad_options);
    ADD_FAILURE() << "accepted";
  } catch (const SettingError& e) {
    EXPECT_EQ(app::error_line(e).rfind("--color-range: expected percentiles", 0), 0u)
        << app::error_line(e);
  }
  // The positional argument is a mesh unless it is a scene file.
  CLI::App mesh;
  app::SceneOptions mesh_options;
  app::add_scene_options(mesh, mesh_options);
  mesh.parse(std::vector<std::string>{"data/meshes/bunny00.off"});
  EXPECT_EQ(app::scene_from_command_line(mesh_options).mesh, "data/meshes/bunny00.off");
}

TEST(ViewerScript, ReadsActions) {
  test::TempDir dir;
  test::write_file(dir / "s.txt", "# comment\n\n0 zoom 2\n5 drag 10 -4 3  # trailing\n9 quit\n");
  const std::vector<app::ScriptAction> s = app::read_script(dir / "s.txt");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[1].frame, 5);
  EXPECT_EQ(s[1].verb, "drag");
  EXPECT_EQ(s[1].args, (std::vector<std::string>{"10", "-4", "3"}));
  test::write_file(dir / "b.txt", "x zoom 1\n");
  EXPECT_THROW(app::read_script(dir / "b.txt"), InputError);
  test::write_file(dir / "c.txt", "1 drag 1 2 zero\n");
  EXPECT_THROW(app::read_script(dir / "c.txt"), InputError);
}

}  // namespace
}  // namespace ibfvs

namespace ibfvs {
namespace {

// The overlay goes on live in the viewer (one door: the Session), and its
// legend and features show in the window's picture; off again, they go.
TEST_F(ViewCommand, TheTopologyOverlayGoesOnAndOffLive) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run missing (Debian package xvfb)";
  const Result v = view_under_xvfb("torus --field gradient:down:1,0.5,0.137 --size 200x200",
                                   "5 screenshot off.png\n"
                                   "5 set overlay topology\n"
                                   "10 screenshot on.png\n"
                                   "10 set overlay none\n"
                                   "15 screenshot again.png\n"
                                   "16 quit\n");
  ASSERT_EQ(v.status, 0) << v.out << v.err;
  // The kinds' colours: the saddles' yellow, the lines' red and blue.
  for (const char* name : {"off.png", "on.png", "again.png"}) {
    const ImageU8 im = read_png(dir_ / name);
    const bool on = std::string(name) == "on.png";
    const std::size_t yellow = test::pixels_of_colour(im, 255, 221, 0),
                      red = test::pixels_of_colour(im, 220, 20, 30),
                      blue = test::pixels_of_colour(im, 30, 90, 255);
    if (on) {
      EXPECT_GT(yellow, 10u) << name;
      EXPECT_GT(red, 20u) << name;
      EXPECT_GT(blue, 20u) << name;
    } else {
      EXPECT_EQ(yellow + red + blue, 0u) << name;
    }
  }
}

}  // namespace
}  // namespace ibfvs
