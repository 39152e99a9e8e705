// Scene files: every example in scenes/ renders, and bad scenes fail with the
// line number.

#include <filesystem>

#include <gtest/gtest.h>

#include "command_runner.h"

namespace ibfvs {
namespace {

using SceneCommand = test::CommandTest;

TEST_F(SceneCommand, EveryExampleSceneRenders) {
  if (!std::filesystem::exists(std::string(IBFVS_TEST_DATA_DIR) + "/earth/etopo20.cdf"))
    GTEST_SKIP() << "fetched data missing (scripts/fetch_data.sh)";
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(IBFVS_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    ++scenes;
    // Small and short, with the command line overriding the scene.
    const test::Result r =
        run("render '" + entry.path().string() + "' --size 64x64 --frames 3 --out s.png",
            "IBFVS_DATA_DIR='" + std::string(IBFVS_TEST_DATA_DIR) + "'");
    EXPECT_EQ(r.status, 0) << entry.path() << "\n" << r.err;
    EXPECT_NE(r.out.find("wrote s.png (3 frames, 64x64)"), std::string::npos) << r.out;
  }
  EXPECT_GE(scenes, 11);  // figures 2-9
}

TEST_F(SceneCommand, SettingsApplyAndTheCommandLineOverrides) {
  file("sq.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  file("s.toml",
       "mesh = \"sq.off\"\nfield = \"uniform:1,0,0\"\nsize = [48, 32]\nframes = 4\n"
       "background = [0.2, 0.3, 0.4]\northo = true\nout = \"a.png\"\n"
       "displace = \"x:0.1\"\n");
  const test::Result a = run("render s.toml");
  ASSERT_EQ(a.status, 0) << a.err;
  EXPECT_NE(a.out.find("wrote a.png (4 frames, 48x32)"), std::string::npos) << a.out;
  const test::Result b = run("render s.toml --frames 2 --out b.png");
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_NE(b.out.find("wrote b.png (2 frames, 48x32)"), std::string::npos) << b.out;
}

TEST_F(SceneCommand, BadScenesNameTheLine) {
  file("sq.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  file("unknown.toml", "mesh = \"sq.off\"\n\nalpah = 0.2\n");
  expect_error("render unknown.toml", "unknown.toml:3: unknown key 'alpah'");
  file("type.toml", "mesh = \"sq.off\"\nframes = \"many\"\n");
  expect_error("render type.toml", "type.toml:2: 'frames' must be an integer");
  file("syntax.toml", "mesh = \"sq.off\"\nalpha = = 0.1\n");
  expect_error("render syntax.toml", "syntax.toml:2:");
  file("size.toml", "mesh = \"sq.off\"\nsize = [-5, 10]\nout = \"x.png\"\n");
  expect_error("render size.toml", "--size");
  file("element.toml", "mesh = \"sq.off\"\n[[element]]\na = [0, 0]\nb = [0, 0, 1]\n");
  expect_error("render element.toml", "element.toml:2: element 'a' must be [x, y, z]");
  file("zero.toml",
       "mesh = \"sq.off\"\nout = \"x.png\"\n[[element]]\na = [0, 0, 0]\nb = [0, 0, 0]\n"
       "rotational = 1\n");
  expect_error("render zero.toml", "the flow element has zero length");
  expect_error("render missing.toml", "missing.toml: no such scene file");
}

}  // namespace
}  // namespace ibfvs
