#include "ibfvs/view_command.h"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include <epoxy/gl.h>
#include <CLI/CLI.hpp>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <glm/trigonometric.hpp>

#include "ibfvs/core/colormap.h"
#include "ibfvs/core/displacement.h"
#include "ibfvs/core/error.h"
#include "ibfvs/core/image.h"
#include "ibfvs/core/noise.h"
#include "ibfvs/core/potential_flow.h"
#include "ibfvs/core/scene.h"
#include "ibfvs/core/scene_prep.h"
#include "ibfvs/core/text.h"
#include "ibfvs/core/vector_field.h"
#include "ibfvs/gl/window.h"
#include "ibfvs/render/session.h"
#include "ibfvs/video_writer.h"
#include "ibfvs/viewer_state.h"

namespace ibfvs::app {
namespace {

constexpr int kPanelWidth = 250;  // the side panel, in window units

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

// The window, the engine and the interaction state, one frame at a time.
class Viewer {
 public:
  Viewer(const ViewOptions& options, Scene desc, PreparedScene prepared)
      : options_(options),
        desc_(std::move(desc)),
        // The panel sits beside the image, not over it.
        window_(prepared.width + (options.no_panel ? 0 : kPanelWidth), prepared.height,
                "ibfvs view", options.vsync),
        session_(std::make_unique<Session>(std::move(prepared))),
        camera_(mesh_bounds(*scene().mesh), scene().camera,
                static_cast<float>(scene().width) / static_cast<float>(scene().height)),
        drag_mode_(parse_enum<DragMode>(options.drag)),
        show_panel_(!options.no_panel) {
    if (!options.script.empty()) script_ = read_script(options.script);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
    glfwSetScrollCallback(window_.handle(), on_scroll);
    ImGui_ImplGlfw_InitForOpenGL(window_.handle(), false);
    ImGui_ImplOpenGL3_Init("#version 450 core");
  }

  ~Viewer() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }

  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  int run() {
    Keys keys(window_.handle());
    const auto started = std::chrono::steady_clock::now();
    int frames_shown = 0;
    auto last_title = std::chrono::steady_clock::now();
    int frames_since_title = 0;
    while (!window_.should_close()) {
      gl::WindowContext::poll_events();
      run_script();
      if (window_.should_close()) break;
      handle_keys(keys);
      handle_mouse();
      if (!paused_) {
        if (scene().step_count > 1) {
          time_ += 1.0 / desc_.frames_per_step;
          session_->seek(time_);
        }
        render();
      }
      int w = 0, h = 0;
      window_.framebuffer_size(w, h);
      int ww = 0, wh = 0;
      glfwGetWindowSize(window_.handle(), &ww, &wh);
      renderer().present(w, h, show_panel_ ? kPanelWidth * w / std::max(ww, 1) : 0);
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
                      scene().mesh_name.c_str(), frames_since_title / seconds,
                      std::string(enum_name(drag_mode_)).c_str(),
                      renderer().locked() ? " - locked" : "");
        window_.set_title(title);
        fps_ = frames_since_title / seconds;
        frames_since_title = 0;
        last_title = now;
      }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (!desc_.quiet)
      std::printf("ibfvs: viewed %s for %d frames at %.1f fps (%dx%d) on %s\n",
                  scene().mesh_name.c_str(), frames_shown, frames_shown / std::max(seconds, 1e-9),
                  scene().width, scene().height, window_.renderer().c_str());
    return 0;
  }

 private:
  const ViewOptions& options_;
  Scene desc_;  // the scene in force, typed: panel, script and loads edit it; save writes it
  gl::WindowContext window_;
  std::unique_ptr<Session> session_;  // renderer, field player and frame count
  ViewerCamera camera_;
  DragMode drag_mode_;
  bool show_panel_ = true, show_help_ = false, paused_ = false;
  bool dragging_ = false, locked_by_drag_ = false;
  glm::vec2 last_cursor_{0.0f};
  double last_click_ = -1.0;
  double time_ = 0.0;
  double fps_ = 0.0;
  int screenshots_ = 0;  // the number in the next ibfvs-view-NNNN file
  std::vector<ScriptAction> script_;
  std::size_t next_action_ = 0;
  struct ScriptDrag {
    glm::vec2 per_frame{0.0f};
    int frames_left = 0;
  } script_drag_;
  std::string save_path_ = "view.toml";
  std::string window_shot_;  // a window capture due after this frame's interface
  std::string message_;      // the last error or note, shown in the panel
  std::string load_path_;
  int selected_element_ = -1;
  bool elements_edited_ = false;
  std::unique_ptr<VideoWriter> video_;
  int snapshot_size_[2] = {2048, 2048};

  PreparedScene& scene() { return session_->scene(); }
  IbfvsRenderer& renderer() { return session_->renderer(); }

  void render() {
    const Camera c = camera_.camera();
    session_->render(c);
    if (video_) {
      ImageU8 frame = video_->spare();
      renderer().read_output(frame);
      video_->write(std::move(frame));
    }
  }

  // Prepares `desc` and, when that succeeds, replaces the current scene
  // (styles, loading a mesh or a scene, settings that change the mesh or the
  // field). Errors go to the panel; the old scene stays.
  bool reload(const Scene& desc) {
    try {
      PreparedScene prepared = prepare_scene(desc);
      for (const std::string& w : prepared.warnings)
        std::fprintf(stderr, "ibfvs: warning: %s\n", w.c_str());
      session_ = std::make_unique<Session>(std::move(prepared));
      desc_ = desc;
      camera_ =
          ViewerCamera(mesh_bounds(*scene().mesh), scene().camera,
                       static_cast<float>(scene().width) / static_cast<float>(scene().height));
      elements_edited_ = false;
      selected_element_ = -1;
      time_ = 0.0;
      message_ = "loaded " + scene().mesh_name;
      return true;
    } catch (const std::exception& e) {
      message_ = std::string("error: ") + e.what();
      std::fprintf(stderr, "ibfvs: %s\n", message_.c_str());
      return false;
    }
  }

  void apply_style(const std::string& name) {
    Scene desc = desc_;
    ibfvs::apply_style(desc, parse_enum<Style>(name));  // the preset wins
    if (reload(desc)) message_ = "style " + name;
  }

  void load(const std::string& path) {
    try {
      if (is_scene_path(path)) {
        reload(read_scene(path));
        return;
      }
    } catch (const std::exception& e) {
      message_ = std::string("error: ") + e.what();
      return;
    }
    Scene desc = desc_;
    desc.mesh = path;
    desc.field_steps.clear();
    reload(desc);
  }

  // Flow elements changed: the field is evaluated again and uploaded.
  void elements_changed() {
    FieldSpec& spec = scene().field_spec;
    if (spec.kind != FieldKind::Elements) {
      spec = FieldSpec::parse("elements");
      message_ = "the field is now the flow elements";
    }
    try {
      for (const FlowElement& e : spec.elements) e.validate();
      session_->set_field(evaluate_field(*scene().mesh, spec, desc_.tangent));
      // The typed scene follows, so that saving keeps the edited elements.
      desc_.field = spec;
      desc_.field->elements.clear();
      desc_.elements = spec.elements;
      elements_edited_ = true;
      update_dt();
    } catch (const std::exception& e) {
      message_ = std::string("error: ") + e.what();
    }
  }

  // The surface point under the cursor (window coordinates), if any: the
  // image fills the window right of the panel, its aspect kept (as present).
  std::optional<glm::vec3> surface_point(glm::vec2 cursor) {
    const ImageF depth = renderer().read_depth();
    int ww = 0, wh = 0;
    glfwGetWindowSize(window_.handle(), &ww, &wh);
    const float left = show_panel_ ? static_cast<float>(kPanelWidth) : 0.0f;
    const float area = std::max(static_cast<float>(ww) - left, 1.0f);
    const float scale = std::min(area / static_cast<float>(scene().width),
                                 static_cast<float>(wh) / static_cast<float>(scene().height));
    const float x0 = left + 0.5f * (area - scale * static_cast<float>(scene().width));
    const float y0 = 0.5f * (static_cast<float>(wh) - scale * static_cast<float>(scene().height));
    const int px = static_cast<int>(std::floor((cursor.x - x0) / scale));
    const int py = scene().height - 1 - static_cast<int>(std::floor((cursor.y - y0) / scale));
    if (px < 0 || py < 0 || px >= scene().width || py >= scene().height) return std::nullopt;
    const float z = depth.pixels[static_cast<std::size_t>(py) * scene().width + px];
    if (z >= 1.0f) return std::nullopt;  // background
    const Camera c = camera_.camera();
    const glm::vec4 ndc(2.0f * (px + 0.5f) / scene().width - 1.0f,
                        2.0f * (py + 0.5f) / scene().height - 1.0f, 2.0f * z - 1.0f, 1.0f);
    const glm::vec4 world = glm::inverse(c.view_projection()) * ndc;
    return glm::vec3(world) / world.w;
  }

  // The current state rendered offscreen at another size: a renderer of
  // that size runs `frames` frames with the current camera and parameters
  // (the texture needs about 22 to form, section 3.7) and writes its image.
  void snapshot(int width, int height, const std::string& file, int frames = 60) {
    PreparedScene big = scene();
    big.settings = renderer().settings();
    big.settings.width = big.width = width;
    big.settings.height = big.height = height;
    Session offscreen(std::move(big));
    ViewerCamera cam = camera_;
    cam.set_aspect(static_cast<float>(width) / static_cast<float>(height));
    const Camera c = cam.camera();
    offscreen.set_dt(dt_for(c, width, height));  // the same pixels per frame as the window
    offscreen.seek(time_);
    for (int k = 0; k < frames; ++k) offscreen.render(c);
    write_png(offscreen.read_output(), file);
    message_ = "wrote " + file;
    std::printf("ibfvs: wrote %s (%dx%d)\n", file.c_str(), width, height);
  }

  void toggle_recording() {
    if (video_) {
      video_->close();
      video_.reset();
      message_ = "recording saved";
      return;
    }
    const std::string name = numbered_name(".mp4");
    try {
      video_ = std::make_unique<VideoWriter>(name, scene().width, scene().height, 30.0);
      message_ = std::string("recording ") + name;
    } catch (const std::exception& e) {
      message_ = std::string("error: ") + e.what();
    }
  }

  // Section 3.7: what the texture does while the user drags.
  void begin_drag() {
    dragging_ = true;
    if (drag_mode_ == DragMode::Freeze && !renderer().locked()) {
      renderer().lock();
      locked_by_drag_ = true;
    }
    RenderSettings s = renderer().settings();
    s.advect_view = drag_mode_ == DragMode::Previous ? AdvectView::Previous : AdvectView::Current;
    renderer().update_settings(s);
  }

  void drag_by(glm::vec2 pixels, bool pan) {
    if (pan)
      camera_.pan(pixels, scene().height);
    else
      camera_.rotate(pixels);
    if (drag_mode_ == DragMode::Translate) {
      // The paper's option: move F_t and G with the pointer (exact for a pan).
      renderer().shift_image(pixels);
    }
  }

  void end_drag() {
    dragging_ = false;
    if (locked_by_drag_) {
      renderer().unlock();
      locked_by_drag_ = false;
    }
    RenderSettings s = renderer().settings();
    s.advect_view = scene().settings.advect_view;
    renderer().update_settings(s);
  }

  void zoom(float steps) {
    camera_.zoom(steps);
    update_dt();
  }

  // The fastest motion back to --step pixels a frame, after a zoom (which
  // would stretch it) or a new field (as render sets dt).
  void update_dt() {
    if (desc_.dt > 0.0f) return;  // the user's own dt stays
    const float dt = dt_for(camera_.camera(), scene().width, scene().height);
    if (dt > 0.0f) session_->set_dt(dt);
  }

  // dt that moves the fastest vertex step pixels in a width x height image.
  float dt_for(const Camera& c, int width, int height) const {
    return dt_for_pixel_step(session_->scene().mesh->positions, session_->scene().field,
                             c.view_projection(), width, height, desc_.step);
  }

  // ibfvs-view-NNNN.EXT in the current folder, numbered on from the last one.
  std::string numbered_name(const char* extension) {
    char name[64];
    std::snprintf(name, sizeof name, "ibfvs-view-%04d%s", screenshots_++, extension);
    return name;
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
    std::vector<FlowElement>& elements = scene().field_spec.elements;
    if (ctrl && left && !over_panel && !dragging_ && selected_element_ >= 0 &&
        selected_element_ < static_cast<int>(elements.size())) {
      // Ctrl + drag: the selected element follows the surface under the pointer.
      if (const auto p = surface_point(cursor)) {
        FlowElement& e = elements[static_cast<std::size_t>(selected_element_)];
        const glm::vec3 half = 0.5f * (e.b - e.a);
        e.a = *p - half;
        e.b = *p + half;
        elements_changed();
      }
    } else if ((left || right) && !dragging_ && !over_panel) {
      begin_drag();
      last_cursor_ = cursor;
      const double now = glfwGetTime();
      if (left && last_click_ >= 0 && now - last_click_ < 0.3) recentre_at(cursor);
      last_click_ = left ? now : -1.0;
    } else if (dragging_ && (left || right)) {
      const glm::vec2 d(cursor.x - last_cursor_.x, last_cursor_.y - cursor.y);  // y up
      if (d != glm::vec2(0.0f)) drag_by(d, right || shift);
      last_cursor_ = cursor;
    } else if (dragging_ && script_drag_.frames_left == 0) {
      end_drag();
    }
    if (g_scroll != 0.0 && !over_panel) zoom(static_cast<float>(g_scroll));
    g_scroll = 0.0;
  }

  // Double-click: the surface point under the cursor becomes the centre.
  void recentre_at(glm::vec2 cursor) {
    if (const auto p = surface_point(cursor)) camera_.recentre(*p);
  }

  void handle_keys(Keys& keys) {
    if (ImGui::GetIO().WantCaptureKeyboard) return;
    if (keys.pressed(GLFW_KEY_Q) || keys.pressed(GLFW_KEY_ESCAPE)) window_.request_close();
    if (keys.pressed(GLFW_KEY_SPACE)) paused_ = !paused_;
    if (keys.pressed(GLFW_KEY_L)) toggle_lock();
    if (keys.pressed(GLFW_KEY_M))
      drag_mode_ =
          enum_entries<DragMode>()[(enum_index(drag_mode_) + 1) % enum_entries<DragMode>().size()]
              .value;
    if (keys.pressed(GLFW_KEY_R)) camera_.reset();
    if (keys.pressed(GLFW_KEY_S)) {
      const std::string name = numbered_name(".png");
      screenshot(name);
    }
    if (keys.pressed(GLFW_KEY_P)) show_panel_ = !show_panel_;
    if (keys.pressed(GLFW_KEY_H)) show_help_ = !show_help_;
  }

  void toggle_lock() {
    if (renderer().locked())
      renderer().unlock();
    else
      renderer().lock();
  }

  void screenshot(const std::string& file) {
    write_png(renderer().read_output(), file);
    std::printf("ibfvs: wrote %s\n", file.c_str());
  }

  // Any scene key, as the script's `set` uses it: texture settings change
  // live, the step rescales dt, anything else prepares the scene again.
  void set(const std::string& key, const std::string& value) {
    Scene desc = desc_;
    apply_setting(desc, key, value);
    static const std::set<std::string, std::less<>> live = {
        "alpha",         "beta",        "vg",          "profile",    "background",
        "surface_color", "color_map",   "color_range", "beta_range", "advect_view",
        "inject",        "spike_width", "noise_space"};
    if (key == "step") {
      session_->set_dt(session_->dt() * desc.step / desc_.step);
      desc_ = desc;
    } else if (live.count(key)) {
      apply_live(desc);
    } else {
      if (!reload(desc)) throw InputError(message_);
    }
  }

  // Texture settings of `desc` that the renderer takes without a rebuild.
  void apply_live(const Scene& desc) {
    RenderSettings s = renderer().settings();
    s.alpha = desc.alpha;
    s.beta = desc.beta;
    s.noise.rate = desc.vg;
    s.noise.profile = desc.profile;
    s.noise.spike_width = desc.spike_width;
    s.background = desc.background;
    s.surface_color = desc.surface_color;
    s.color_map = desc.color_map;
    s.inject = desc.inject;
    s.advect_view = desc.advect_view;
    if (desc.color_range && !desc.color_range->percentile)
      s.color_range = {desc.color_range->lo, desc.color_range->hi};
    if (desc.beta_range && !desc.beta_range->percentile)
      s.beta_range = {desc.beta_range->lo, desc.beta_range->hi};
    if ((desc.noise_space == NoiseSpace::Object) != s.object_noise) {
      s.object_noise = desc.noise_space == NoiseSpace::Object;
      // s pixels at the distance of the mesh centre, as prepare_scene does.
      const Camera c = camera_.camera();
      s.object_cell = s.noise.scale * 2.0f * c.distance_world() *
                      std::tan(glm::radians(c.params().fov_deg) * 0.5f) /
                      static_cast<float>(scene().height);
    }
    s.validate();
    renderer().update_settings(s);
    scene().settings = s;
    desc_ = desc;
  }

  // The typed scene in force, with the camera, size and frame count of now:
  // `ibfvs render SAVED.toml` gives this frame.
  void save_scene(const std::string& file) {
    Scene desc = desc_;
    const CameraParams& p = camera_.params();
    const float diagonal = std::max(camera_.bounds().diagonal(), 1e-6f);
    desc.camera.azimuth_deg = p.azimuth_deg;
    desc.camera.elevation_deg = p.elevation_deg;
    desc.camera.distance = p.distance > 0.0f ? camera_.camera().distance_world() / diagonal : 0.0f;
    desc.camera.target = p.target;
    desc.frames = std::max(renderer().frame(), 1);
    desc.width = scene().width;
    desc.height = scene().height;
    if (desc.lock_at == Scene::kLockAuto) desc.lock_at = scene().lock_at;
    desc.style.reset();
    std::ofstream out(file);
    out << scene_toml(desc);
    if (!out) throw InputError(file + ": cannot write the scene");
    std::printf("ibfvs: saved %s (frame %d)\n", file.c_str(), renderer().frame());
  }

  void run_script() {
    if (script_drag_.frames_left > 0) {
      drag_by(script_drag_.per_frame, false);
      if (--script_drag_.frames_left == 0) end_drag();
    }
    while (next_action_ < script_.size() && script_[next_action_].frame <= renderer().frame()) {
      const ScriptAction& a = script_[next_action_++];
      const auto number = [&](std::size_t i) { return parse_numbers(a.args[i])[0]; };
      if (a.verb == "drag") {
        begin_drag();
        script_drag_.frames_left = static_cast<int>(number(2));
        script_drag_.per_frame =
            glm::vec2(number(0), number(1)) / static_cast<float>(script_drag_.frames_left);
      } else if (a.verb == "zoom") {
        zoom(number(0));
      } else if (a.verb == "pan") {
        camera_.pan({number(0), number(1)}, scene().height);
      } else if (a.verb == "set") {
        set(a.args[0], a.args[1]);
      } else if (a.verb == "mode") {
        drag_mode_ = parse_enum<DragMode>(a.args[0]);
      } else if (a.verb == "lock") {
        renderer().lock();
      } else if (a.verb == "unlock") {
        renderer().unlock();
      } else if (a.verb == "screenshot") {
        screenshot(a.args[0]);
      } else if (a.verb == "style") {
        apply_style(a.args[0]);
      } else if (a.verb == "load") {
        load(a.args[0]);
      } else if (a.verb == "element") {
        std::vector<FlowElement> kept = scene().field_spec.elements;
        kept.push_back(FlowElement::parse(a.args[0]));
        if (scene().field_spec.kind != FieldKind::Elements)
          scene().field_spec = FieldSpec::parse("elements");
        scene().field_spec.elements = kept;
        elements_changed();
      } else if (a.verb == "snapshot") {
        const std::vector<float> n = parse_numbers(a.args[0], 2, "W,H");
        const glm::vec2 size(n[0], n[1]);
        if (!(size.x >= 1 && size.y >= 1 && size.x <= 16384 && size.y <= 16384))
          throw InputError("snapshot: the size must be within 1..16384 pixels");
        snapshot(static_cast<int>(size.x), static_cast<int>(size.y), a.args[1]);
      } else if (a.verb == "record") {
        toggle_recording();
      } else if (a.verb == "window") {
        window_shot_ = a.args[0];
      } else if (a.verb == "help") {
        show_help_ = !show_help_;
      } else if (a.verb == "texture") {
        write_png16(renderer().read_texture().select_channels(0, 3), a.args[0]);
      } else if (a.verb == "save") {
        save_scene(a.args[0]);
      } else if (a.verb == "quit") {
        window_.request_close();
        return;
      }
    }
  }

  void draw_interface() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (show_panel_) draw_panel();
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

  void draw_panel() {
    // A side bar left of the image (the window is that much wider), so it
    // never hides the mesh.
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(kPanelWidth), display.y), ImGuiCond_Always);
    char title[64];
    std::snprintf(title, sizeof title, "ibfvs %.0f fps###ibfvs", fps_);
    ImGui::Begin(title, &show_panel_,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(130);
    Scene d = desc_;
    bool changed = false;
    changed |= ImGui::SliderFloat("alpha", &d.alpha, 0.0f, 1.0f, "%.2f");
    changed |= ImGui::SliderFloat("beta", &d.beta, 0.0f, 1.0f, "%.2f");
    changed |= ImGui::SliderFloat("v_g", &d.vg, 0.0f, 0.2f, "%.3f");
    changed |= enum_combo("profile", d.profile);
    const ImGuiColorEditFlags swatch = ImGuiColorEditFlags_NoInputs;
    changed |= ImGui::ColorEdit3("bg", &d.background.x, swatch);
    ImGui::SameLine();
    changed |= ImGui::ColorEdit3("surface", &d.surface_color.x, swatch);
    if (changed) apply_live(d);
    enum_combo("drag", drag_mode_);
    bool locked = renderer().locked();
    if (ImGui::Checkbox("lock", &locked)) toggle_lock();
    ImGui::SameLine();
    ImGui::Checkbox("pause", &paused_);
    if (ImGui::SmallButton("reset view")) camera_.reset();
    ImGui::SameLine();
    if (ImGui::SmallButton("restart")) renderer().reset();
    ImGui::SameLine();
    if (ImGui::SmallButton("help")) show_help_ = !show_help_;
    if (scene().step_count > 1) {
      // Unsteady data (months on the globe): play with pause, step, slide.
      float t = static_cast<float>(time_);
      if (ImGui::SliderFloat("time", &t, 0.0f, static_cast<float>(scene().step_count) - 0.01f)) {
        time_ = t;
        session_->seek(time_);
      }
      if (ImGui::SmallButton("<")) time_ = std::floor(time_) - 1.0 + scene().step_count;
      ImGui::SameLine();
      if (ImGui::SmallButton(">")) time_ = std::floor(time_) + 1.0;
      ImGui::SameLine();
      ImGui::Text("step %d of %zu", static_cast<int>(time_) % static_cast<int>(scene().step_count),
                  scene().step_count);
      session_->seek(time_);
    }
    if (ImGui::CollapsingHeader("More parameters")) draw_more_parameters();
    if (ImGui::CollapsingHeader("Styles and files")) draw_styles_and_files();
    if (ImGui::CollapsingHeader("Flow elements")) draw_elements();
    if (ImGui::CollapsingHeader("Save and record")) draw_save_and_record();
    if (!message_.empty()) {
      ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 200);
      ImGui::TextUnformatted(message_.c_str());
      ImGui::PopTextWrapPos();
    }
    ImGui::PopItemWidth();
    ImGui::End();
  }

  // Scene file, screenshot, recording, an offscreen render at any size.
  void draw_save_and_record() {
    ImGui::Text("frame %d, %zu triangles", renderer().frame(), scene().mesh->triangle_count());
    char path[256];
    std::snprintf(path, sizeof path, "%s", save_path_.c_str());
    ImGui::SetNextItemWidth(140);
    if (ImGui::InputText("##scene file", path, sizeof path)) save_path_ = path;
    ImGui::SameLine();
    if (ImGui::SmallButton("save scene")) save_scene(save_path_);
    if (ImGui::SmallButton("screenshot")) {
      const std::string name = numbered_name(".png");
      screenshot(name);
    }
    ImGui::SameLine();
    if (ImGui::SmallButton(video_ ? "stop recording" : "record")) toggle_recording();
    ImGui::SetNextItemWidth(110);
    ImGui::InputInt2("##snapshot size", snapshot_size_);
    ImGui::SameLine();
    if (ImGui::SmallButton("render offscreen")) {
      const std::string name = numbered_name(".png");
      try {
        snapshot(std::clamp(snapshot_size_[0], 1, 16384), std::clamp(snapshot_size_[1], 1, 16384),
                 name);
      } catch (const std::exception& e) {
        message_ = std::string("error: ") + e.what();
      }
    }
  }

  // A combo box over an enum's name table; true when the choice changed.
  template <class E>
  static bool enum_combo(const char* label, E& value) {
    const std::vector<EnumName<E>> entries = enum_entries<E>();
    int index = enum_index(value);
    const std::string preview(index >= 0 ? entries[static_cast<std::size_t>(index)].name : "?");
    bool changed = false;
    if (ImGui::BeginCombo(label, preview.c_str())) {
      for (std::size_t i = 0; i < entries.size(); ++i) {
        const std::string name(entries[i].name);
        if (ImGui::Selectable(name.c_str(), static_cast<int>(i) == index)) {
          changed = entries[i].value != value;
          value = entries[i].value;
        }
        if (ImGui::IsItemHovered())
          ImGui::SetTooltip("%s", std::string(entries[i].description).c_str());
      }
      ImGui::EndCombo();
    }
    return changed;
  }

  // s, step, noise space, tangent mode, colour map and ranges.
  void draw_more_parameters() {
    Scene d = desc_;
    if (ImGui::SliderFloat("s (noise scale)", &d.scale, 1.0f, 16.0f) && d.scale != desc_.scale) {
      // A new grid: the texture starts again.
      desc_.scale = d.scale;
      scene().settings = renderer().settings();
      scene().settings.noise.scale = d.scale;
      session_->rebuild();
      return;
    }
    if (ImGui::SliderFloat("step (px/frame)", &d.step, 0.25f, 8.0f) && d.step > 0.0f)
      set("step", format_number(d.step));
    if (enum_combo("noise space", d.noise_space)) apply_live(d);
    if (enum_combo("tangent", d.tangent)) {
      try {
        session_->set_field(evaluate_field(*scene().mesh, scene().field_spec, d.tangent));
        desc_.tangent = d.tangent;
      } catch (const std::exception& e) {
        message_ = std::string("error: ") + e.what();
      }
    }
    RenderSettings s = renderer().settings();
    if (s.use_color) {
      bool changed = enum_combo("colour map", d.color_map);
      if (ImGui::DragFloat2("colour range", &s.color_range.x, 0.01f) &&
          s.color_range.y > s.color_range.x) {
        d.color_range = ScalarRange{false, s.color_range.x, s.color_range.y};
        changed = true;
      }
      if (changed) apply_live(d);
    }
    if (s.use_beta && ImGui::DragFloat2("beta range", &s.beta_range.x, 0.01f) &&
        s.beta_range.y > s.beta_range.x) {
      d.beta_range = ScalarRange{false, s.beta_range.x, s.beta_range.y};
      apply_live(d);
    }
  }

  void draw_styles_and_files() {
    int n = 0;
    for (const EnumName<Style>& style : enum_entries<Style>()) {
      const std::string name(style.name);
      if (n++ % 3 != 0) ImGui::SameLine();
      if (ImGui::Button(name.c_str())) apply_style(name);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(style.description).c_str());
    }
    char path[512];
    std::snprintf(path, sizeof path, "%s", load_path_.c_str());
    if (ImGui::InputText("mesh or scene", path, sizeof path)) load_path_ = path;
    if (ImGui::Button("load") && !load_path_.empty()) load(load_path_);
  }

  // Add, select, move (ctrl + drag on the surface) and shape flow elements.
  void draw_elements() {
    std::vector<FlowElement>& elements = scene().field_spec.elements;
    bool changed = false;
    for (std::size_t i = 0; i < elements.size(); ++i) {
      char label[32];
      std::snprintf(label, sizeof label, "element %zu", i + 1);
      if (ImGui::RadioButton(label, selected_element_ == static_cast<int>(i)))
        selected_element_ = static_cast<int>(i);
    }
    if (ImGui::Button("add")) {
      // A vertical line through the look-at point, a fifth of the mesh long.
      const Bounds& b = camera_.bounds();
      const glm::vec3 c = b.centre() + camera_.params().target;
      const float half = 0.1f * b.diagonal();
      FlowElement e;
      e.a = c - glm::vec3(0, half, 0);
      e.b = c + glm::vec3(0, half, 0);
      e.rotational = 1.0f;
      elements.push_back(e);
      selected_element_ = static_cast<int>(elements.size()) - 1;
      changed = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("remove") && selected_element_ >= 0 &&
        selected_element_ < static_cast<int>(elements.size())) {
      elements.erase(elements.begin() + selected_element_);
      selected_element_ = -1;
      changed = true;
    }
    if (selected_element_ >= 0 && selected_element_ < static_cast<int>(elements.size())) {
      FlowElement& e = elements[static_cast<std::size_t>(selected_element_)];
      changed |= ImGui::SliderFloat("rotational", &e.rotational, -2.0f, 2.0f);
      changed |= ImGui::SliderFloat("radial", &e.radial, -2.0f, 2.0f);
      changed |= ImGui::SliderFloat("tangential", &e.tangential, -2.0f, 2.0f);
      float length = glm::length(e.b - e.a);
      const float diagonal = camera_.bounds().diagonal();
      if (ImGui::SliderFloat("length", &length, 0.01f * diagonal, 2.0f * diagonal)) {
        const glm::vec3 mid = 0.5f * (e.a + e.b), dir = glm::normalize(e.b - e.a);
        e.a = mid - 0.5f * length * dir;
        e.b = mid + 0.5f * length * dir;
        changed = true;
      }
      ImGui::TextUnformatted("ctrl + drag moves it along the surface");
    }
    if (changed) elements_changed();
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
