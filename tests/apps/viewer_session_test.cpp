// The viewer's state driven without a window: settings live and by reload,
// flow elements saved as a scene, drag modes, and scripts through the runner
// with a stand-in for the window. A headless context stands in for the
// window's.

#include <filesystem>
#include <memory>

#include <gtest/gtest.h>

#include "helpers.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/context.h"
#include "ibfvs/script_runner.h"
#include "ibfvs/viewer_session.h"

namespace ibfvs::app {
namespace {

class ViewerSessionTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context_ = std::make_unique<gl::HeadlessContext>(); }
  static void TearDownTestSuite() { context_.reset(); }

  static ViewerSession make(DragMode drag = DragMode::Previous) {
    Scene s;
    s.mesh = "torus";
    s.width = 96;
    s.height = 96;
    apply_setting(s, "camera", "0,50,0");
    return ViewerSession(s, prepare_scene(s), drag);
  }
  test::TempDir dir_;

 private:
  static inline std::unique_ptr<gl::HeadlessContext> context_;
};

TEST_F(ViewerSessionTest, SettingsChangeLiveOrByPreparingTheSceneAgain) {
  ViewerSession v = make();
  for (int k = 0; k < 4; ++k) v.frame();
  v.set("alpha", "0.3");  // live: the texture goes on
  EXPECT_EQ(v.session().settings().alpha, 0.3f);
  EXPECT_EQ(v.desc().alpha, 0.3f);
  v.frame();
  EXPECT_EQ(v.frame_count(), 5);
  v.set("color_map", "bronze");
  EXPECT_EQ(v.session().settings().color_map, ColorMap::Bronze);
  v.set("filter", "5");  // the display stage and the warp change live too
  v.set("contrast", "0");
  v.set("resample", "linear");
  EXPECT_EQ(v.session().settings().filter_length, 5.0f);
  EXPECT_EQ(v.session().settings().contrast, 0.0f);
  EXPECT_EQ(v.session().settings().resample, Resample::Linear);
  v.frame();
  EXPECT_EQ(v.frame_count(), 6) << "not prepared again";
  v.set("mesh", "torus:1,0.2");  // a new mesh: prepared again, frames from 0
  EXPECT_EQ(v.scene().mesh_name, "torus:1,0.2");
  EXPECT_EQ(v.frame_count(), 0);
  EXPECT_EQ(v.desc().alpha, 0.3f);  // what was set before stays
  // A bad value changes nothing.
  EXPECT_THROW(v.set("beta", "2"), SettingError);
  EXPECT_THROW(v.set("nonsense", "1"), SettingError);
  EXPECT_EQ(v.desc().beta, Scene{}.beta);
  // A mesh that cannot be prepared: the message says so, the old one stays.
  EXPECT_THROW(v.set("mesh", "no-such-mesh.off"), InputError);
  EXPECT_EQ(v.scene().mesh_name, "torus:1,0.2");
  EXPECT_NE(v.message.find("no-such-mesh.off"), std::string::npos) << v.message;
}

TEST_F(ViewerSessionTest, EditedElementsAreSavedAsAScene) {
  ViewerSession v = make();
  v.add_element(FlowElement::parse("0,-1,0,0,1,0,1.5,0.5,0"));
  EXPECT_EQ(v.scene().field_spec.kind, FieldKind::Elements);
  EXPECT_EQ(v.selected_element, 0);
  for (int k = 0; k < 3; ++k) v.frame();
  v.save_scene(dir_ / "saved.toml");
  const Scene back = read_scene(dir_ / "saved.toml");
  ASSERT_TRUE(back.field);
  EXPECT_EQ(back.field->kind, FieldKind::Elements);
  ASSERT_EQ(back.elements.size(), 1u);
  EXPECT_EQ(back.elements[0].rotational, 1.5f);
  EXPECT_EQ(back.frames, 3);
  EXPECT_EQ(back.camera.elevation_deg, 50.0f);
  EXPECT_NO_THROW(prepare_scene(back));
}

TEST_F(ViewerSessionTest, FreezeLocksWhileDragging) {
  ViewerSession v = make(DragMode::Freeze);
  v.frame();
  v.begin_drag();
  EXPECT_TRUE(v.session().locked());
  v.drag_by({20.0f, 0.0f}, false);
  EXPECT_EQ(v.camera().params().azimuth_deg, -6.0f);  // 0.3 degrees per pixel
  v.end_drag();
  EXPECT_FALSE(v.session().locked());
}

// The window's part of a script, recorded.
struct FakeWindow final : WindowActions {
  std::vector<std::string> captures;
  int help = 0, quits = 0;
  void capture_window(const std::string& file) override { captures.push_back(file); }
  void toggle_help() override { ++help; }
  void quit() override { ++quits; }
};

TEST_F(ViewerSessionTest, ScriptsRunTheirActionsWhenTheirFrameComes) {
  test::write_file(dir_ / "s.txt",
                   "0 set alpha 0.2\n"
                   "2 drag 30 0 3\n"
                   "2 element 0,-1,0,0,1,0,1,0,0\n"
                   "4 window w.png\n"
                   "4 help\n"
                   "6 quit\n"
                   "7 set alpha 0.9\n");
  ViewerSession v = make();
  ScriptRunner runner(read_script(dir_ / "s.txt"));
  FakeWindow window;
  for (int k = 0; k < 10; ++k) {
    runner.run(v, window);
    v.frame();
  }
  EXPECT_EQ(v.desc().alpha, 0.2f);  // the action after quit never ran
  EXPECT_EQ(window.captures, std::vector<std::string>{"w.png"});
  EXPECT_EQ(window.help, 1);
  EXPECT_EQ(window.quits, 1);
  EXPECT_EQ(v.scene().field_spec.elements.size(), 1u);
  EXPECT_NEAR(v.camera().params().azimuth_deg, -9.0f, 1e-4f);  // 30 px spread over 3 frames
  EXPECT_FALSE(v.dragging());
  EXPECT_TRUE(runner.done());
}

TEST(ScriptVerbs, EveryVerbIsListedOnceWithHelp) {
  const std::vector<ScriptVerbInfo> verbs = script_verbs();
  EXPECT_EQ(verbs.size(), 18u);
  for (std::size_t i = 0; i < verbs.size(); ++i) {
    EXPECT_FALSE(verbs[i].help.empty()) << verbs[i].name;
    for (std::size_t j = 0; j < i; ++j) EXPECT_NE(verbs[i].name, verbs[j].name);
    EXPECT_NE(script_verb_names().find(verbs[i].name), std::string::npos);
  }
}

}  // namespace
}  // namespace ibfvs::app
