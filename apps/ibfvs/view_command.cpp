#include "ibfvs/view_command.h"

// The window and its input: GLFW events and keys, the mouse as the camera and
// the drag modes, the help overlay, the main loop. The state and its actions
// are in ViewerSession, the panel in ViewerPanel, scripts in ScriptRunner.

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include <epoxy/gl.h>
#include <CLI/CLI.hpp>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "ibfvs/core/image/image.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/window.h"
#include "ibfvs/script_runner.h"
#include "ibfvs/viewer_panel.h"
#include "ibfvs/viewer_session.h"

namespace ibfvs::app {
namespace {

const char* const kHelp =
    "left drag      rotate\n"
    "right drag     pan (or shift + left drag)\n"
    "wheel          zoom\n"
    "double-click   recentre on the surface point\n"
    "space          pause / play\n"
    "l              lock / unlock the texture (3.7)\n"
    "m              next drag mode: plain, translate, freeze, previous\n"
    "r              reset the camera\n"
    "s              screenshot (ibfvs-view-NNNN.png)\n"
    "p              show / hide the panel\n"
    "h              show / hide this help\n"
    "q, escape      quit";

double g_scroll = 0.0;  // wheel steps since the last frame (GLFW callback)

void on_scroll(GLFWwindow* window, double dx, double dy) {
  g_scroll += dy;
  ImGui_ImplGlfw_ScrollCallback(window, dx, dy);
}

// Edge detection for keyboard shortcuts.
class Keys {
 public:
  explicit Keys(GLFWwindow* w) : window_(w) {}
  bool pressed(int key) {
    const bool down = glfwGetKey(window_, key) == GLFW_PRESS;
    const bool was = down_[static_cast<std::size_t>(key)];
    down_[static_cast<std::size_t>(key)] = down;
    return down && !was;
  }

 private:
  GLFWwindow* window_;
  std::array<bool, GLFW_KEY_LAST + 1> down_{};
};

// The window: events in, frames and the interface out.
class Viewer final : public WindowActions {
 public:
  Viewer(const ViewOptions& options, Scene desc, PreparedScene prepared)
      : quiet_(desc.quiet),
        // The panel sits beside the image, not over it.
        window_(prepared.width + (options.no_panel ? 0 : ViewerPanel::kWidth), prepared.height,
                "ibfvs view", options.vsync),
        viewer_(std::move(desc), std::move(prepared), parse_enum<DragMode>(options.drag)),
        script_(options.script.empty() ? std::vector<ScriptAction>{} : read_script(options.script)),
        show_panel_(!options.no_panel) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
    glfwSetScrollCallback(window_.handle(), on_scroll);
    ImGui_ImplGlfw_InitForOpenGL(window_.handle(), false);
    ImGui_ImplOpenGL3_Init("#version 450 core");
  }

  ~Viewer() override {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }

  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // ---- WindowActions, for scripts
  void capture_window(const std::string& file) override { window_shot_ = file; }
  void toggle_help() override { show_help_ = !show_help_; }
  void quit() override { window_.request_close(); }

  int run() {
    Keys keys(window_.handle());
    const auto started = std::chrono::steady_clock::now();
    int frames_shown = 0;
    auto last_title = std::chrono::steady_clock::now();
    int frames_since_title = 0;
    while (!window_.should_close()) {
      gl::WindowContext::poll_events();
      script_.run(viewer_, *this);
      if (window_.should_close()) break;
      handle_keys(keys);
      handle_mouse();
      viewer_.frame();
      int w = 0, h = 0;
      window_.framebuffer_size(w, h);
      int ww = 0, wh = 0;
      glfwGetWindowSize(window_.handle(), &ww, &wh);
      viewer_.session().present(w, h, show_panel_ ? ViewerPanel::kWidth * w / std::max(ww, 1) : 0);
      draw_interface();
      if (!window_shot_.empty()) {
        write_png(window_.read_pixels(), window_shot_);
        std::printf("ibfvs: wrote %s\n", window_shot_.c_str());
        window_shot_.clear();
      }
      window_.swap_buffers();
      ++frames_since_title;
      ++frames_shown;
      const auto now = std::chrono::steady_clock::now();
      const double seconds = std::chrono::duration<double>(now - last_title).count();
      if (seconds > 0.5) {
        char title[256];
        std::snprintf(title, sizeof title, "ibfvs view - %s - %.1f fps - drag: %s%s",
                      viewer_.scene().mesh_name.c_str(), frames_since_title / seconds,
                      std::string(enum_name(viewer_.drag_mode)).c_str(),
                      viewer_.session().locked() ? " - locked" : "");
        window_.set_title(title);
        fps_ = frames_since_title / seconds;
        frames_since_title = 0;
        last_title = now;
      }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (!quiet_)
      std::printf("ibfvs: viewed %s for %d frames at %.1f fps (%dx%d) on %s\n",
                  viewer_.scene().mesh_name.c_str(), frames_shown,
                  frames_shown / std::max(seconds, 1e-9), viewer_.scene().width,
                  viewer_.scene().height, window_.renderer().c_str());
    return 0;
  }

 private:
  bool quiet_;
  gl::WindowContext window_;
  ViewerSession viewer_;
  ScriptRunner script_;
  ViewerPanel panel_;
  bool show_panel_ = true, show_help_ = false;
  glm::vec2 last_cursor_{0.0f};
  double last_click_ = -1.0;
  double fps_ = 0.0;
  std::string window_shot_;  // a window capture due after this frame's interface

  // Window coordinates to image pixels (x right, y down): the image fills
  // the window right of the panel, its aspect kept, as present() draws it.
  glm::vec2 image_pixel(glm::vec2 cursor) {
    int ww = 0, wh = 0;
    glfwGetWindowSize(window_.handle(), &ww, &wh);
    const PreparedScene& s = viewer_.scene();
    const float left = show_panel_ ? static_cast<float>(ViewerPanel::kWidth) : 0.0f;
    const float area = std::max(static_cast<float>(ww) - left, 1.0f);
    const float scale = std::min(area / static_cast<float>(s.width),
                                 static_cast<float>(wh) / static_cast<float>(s.height));
    const float x0 = left + 0.5f * (area - scale * static_cast<float>(s.width));
    const float y0 = 0.5f * (static_cast<float>(wh) - scale * static_cast<float>(s.height));
    return {(cursor.x - x0) / scale, (cursor.y - y0) / scale};
  }

  void handle_mouse() {
    GLFWwindow* w = window_.handle();
    double x = 0, y = 0;
    glfwGetCursorPos(w, &x, &y);
    const glm::vec2 cursor(static_cast<float>(x), static_cast<float>(y));
    const bool over_panel = ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse;
    const bool left = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                       glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    const bool shift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
    const bool ctrl = glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                      glfwGetKey(w, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
    std::vector<FlowElement> elements = viewer_.elements();
    const int selected = viewer_.selected_element;
    if (ctrl && left && !over_panel && !viewer_.dragging() && selected >= 0 &&
        selected < static_cast<int>(elements.size())) {
      // Ctrl + drag: the selected element follows the surface under the pointer.
      if (const auto p = viewer_.surface_point(image_pixel(cursor))) {
        FlowElement& e = elements[static_cast<std::size_t>(selected)];
        const glm::vec3 half = 0.5f * (e.b - e.a);
        e.a = *p - half;
        e.b = *p + half;
        viewer_.set_elements(std::move(elements));
      }
    } else if ((left || right) && !viewer_.dragging() && !over_panel) {
      viewer_.begin_drag();
      last_cursor_ = cursor;
      const double now = glfwGetTime();
      // Double-click: the surface point under the cursor becomes the centre.
      if (left && last_click_ >= 0 && now - last_click_ < 0.3)
        if (const auto p = viewer_.surface_point(image_pixel(cursor)))
          viewer_.camera().recentre(*p);
      last_click_ = left ? now : -1.0;
    } else if (viewer_.dragging() && (left || right)) {
      const glm::vec2 d(cursor.x - last_cursor_.x, last_cursor_.y - cursor.y);  // y up
      if (d != glm::vec2(0.0f)) viewer_.drag_by(d, right || shift);
      last_cursor_ = cursor;
    } else if (viewer_.dragging() && !script_.dragging()) {
      viewer_.end_drag();
    }
    if (g_scroll != 0.0 && !over_panel) viewer_.zoom(static_cast<float>(g_scroll));
    g_scroll = 0.0;
  }

  void handle_keys(Keys& keys) {
    if (ImGui::GetIO().WantCaptureKeyboard) return;
    if (keys.pressed(GLFW_KEY_Q) || keys.pressed(GLFW_KEY_ESCAPE)) window_.request_close();
    if (keys.pressed(GLFW_KEY_SPACE)) viewer_.paused = !viewer_.paused;
    if (keys.pressed(GLFW_KEY_L)) viewer_.toggle_lock();
    if (keys.pressed(GLFW_KEY_M)) {
      const std::vector<EnumName<DragMode>> modes = enum_entries<DragMode>();
      viewer_.drag_mode = modes[(enum_index(viewer_.drag_mode) + 1) % modes.size()].value;
    }
    if (keys.pressed(GLFW_KEY_R)) viewer_.camera().reset();
    if (keys.pressed(GLFW_KEY_S)) viewer_.screenshot(viewer_.numbered_name(".png"));
    if (keys.pressed(GLFW_KEY_P)) show_panel_ = !show_panel_;
    if (keys.pressed(GLFW_KEY_H)) show_help_ = !show_help_;
  }

  void draw_interface() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (show_panel_) panel_.draw(viewer_, show_panel_, show_help_, fps_);
    if (show_help_) {
      const ImVec2 size = ImGui::GetIO().DisplaySize;
      ImGui::SetNextWindowPos(ImVec2(size.x - 8, size.y - 8), ImGuiCond_Always, ImVec2(1, 1));
      ImGui::SetNextWindowBgAlpha(0.8f);
      ImGui::Begin("Help", &show_help_, ImGuiWindowFlags_AlwaysAutoResize);
      ImGui::TextUnformatted(kHelp);
      ImGui::End();
    }
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }
};

}  // namespace

void add_view_options(CLI::App& cmd, ViewOptions& o) {
  add_scene_options(cmd, o.scene);
  cmd.add_option("--drag", o.drag,
                 "What the texture does while you drag (paper 3.7): " + enum_name_list<DragMode>() +
                     "; plain: fixed on the screen, translate: F_t and G move with the pointer, "
                     "freeze: locked until release, previous: advected with the last frame's "
                     "view, stays on the surface")
      ->capture_default_str();
  cmd.add_flag("--vsync", o.vsync, "Wait for the display's refresh (default: as fast as it goes)");
  cmd.add_flag("--no-panel", o.no_panel, "Start with the parameter panel hidden (p shows it)");
  cmd.add_option("--script", o.script,
                 "FILE of timed actions (FRAME VERB ARGS per line; verbs: " + script_verb_names() +
                     "), for tests and demos");
}

int run_view(const ViewOptions& o) {
  try {
    parse_enum<DragMode>(o.drag);
  } catch (const InputError& e) {
    throw InputError(std::string("--drag: ") + e.what());
  }
  if (!o.script.empty()) read_script(o.script);  // errors before any window
  Scene desc = scene_from_command_line(o.scene);
  if (!gl::display_available())
    throw InputError(
        "no display: DISPLAY and WAYLAND_DISPLAY are unset, so ibfvs view cannot open a "
        "window; use ibfvs render for pictures and videos without one");
  PreparedScene prepared = prepare_scene(desc);
  for (const std::string& w : prepared.warnings)
    std::fprintf(stderr, "ibfvs: warning: %s\n", w.c_str());
  Viewer viewer(o, std::move(desc), std::move(prepared));
  return viewer.run();
}

}  // namespace ibfvs::app
