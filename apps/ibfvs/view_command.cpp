#include "ibfvs/view_command.h"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
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
#include "ibfvs/core/vector_field.h"
#include "ibfvs/gl/window.h"
#include "ibfvs/scene.h"
#include "ibfvs/styles.h"
#include "ibfvs/video_writer.h"
#include "ibfvs/viewer_state.h"

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

// The window, the engine and the interaction state, one frame at a time.
class Viewer {
 public:
  Viewer(const ViewOptions& options, PreparedScene scene)
      : options_(options),
        render_(options.render),
        args_(render_arguments_of(options.arguments)),
        scene_(std::move(scene)),
        window_(scene_.width, scene_.height, "ibfvs view", options.vsync),
        camera_(mesh_bounds(*scene_.mesh), scene_.camera,
                static_cast<float>(scene_.width) / static_cast<float>(scene_.height)),
        drag_mode_(parse_drag_mode(options.drag)),
        show_panel_(!options.no_panel) {
    if (!options.script.empty()) script_ = read_script(options.script);
    make_renderer();
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
        if (scene_.step_count > 1) {
          time_ += 1.0 / render_.frames_per_step;
          player_->seek(time_, *renderer_);
        }
        render();
      }
      int w = 0, h = 0;
      window_.framebuffer_size(w, h);
      renderer_->present(w, h);
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
                      scene_.mesh_name.c_str(), frames_since_title / seconds,
                      to_string(drag_mode_).c_str(), renderer_->locked() ? " - locked" : "");
        window_.set_title(title);
        fps_ = frames_since_title / seconds;
        frames_since_title = 0;
        last_title = now;
      }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (!render_.quiet)
      std::printf("ibfvs: viewed %s for %d frames at %.1f fps (%dx%d) on %s\n",
                  scene_.mesh_name.c_str(), frames_shown, frames_shown / std::max(seconds, 1e-9),
                  scene_.width, scene_.height, window_.renderer().c_str());
    return 0;
  }

 private:
  const ViewOptions& options_;
  RenderOptions render_;           // the render options in force (styles and loads change them)
  std::vector<std::string> args_;  // the same as arguments, for reloading and saving
  PreparedScene scene_;
  gl::WindowContext window_;
  ViewerCamera camera_;
  std::unique_ptr<IbfvsRenderer> renderer_;
  std::unique_ptr<FieldPlayer> player_;
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
  std::string window_shot_;       // a window capture due after this frame's interface
  float step_px_ = render_.step;  // --step, changed by `set step`
  std::string message_;           // the last error or note, shown in the panel
  std::string load_path_;
  int selected_element_ = -1;
  bool elements_edited_ = false;
  std::unique_ptr<VideoWriter> video_;
  int snapshot_size_[2] = {2048, 2048};

  void make_renderer() {
    player_.reset();
    renderer_ = std::make_unique<IbfvsRenderer>(scene_.settings);
    load_scene(*renderer_, scene_, render_);
    player_ = std::make_unique<FieldPlayer>(scene_, *renderer_);
  }

  void render() {
    const Camera c = camera_.camera();
    renderer_->render_frame({c.view(), c.projection()}, scene_.dt);
    if (video_) {
      ImageU8 frame = video_->spare();
      renderer_->read_output(frame);
      video_->write(std::move(frame));
    }
  }

  static std::string numbers(std::initializer_list<float> values) {
    std::string out;
    char one[32];
    for (const float v : values) {
      std::snprintf(one, sizeof one, "%s%.6g", out.empty() ? "" : ",", v);
      out += one;
    }
    return out;
  }

  // Parses render arguments as `ibfvs render` does and, when the scene they
  // describe prepares without error, replaces the current one (styles, loading
  // a mesh or a scene). Errors go to the panel; the old scene stays.
  bool reload(const std::vector<std::string>& args) {
    try {
      CLI::App parser;
      RenderOptions options;
      add_render_options(parser, options);
      std::vector<std::string> reversed(args.rbegin(), args.rend());
      parser.parse(reversed);
      PreparedScene scene = prepare_scene(options);
      render_ = options;
      args_ = args;
      scene_ = std::move(scene);
      camera_ = ViewerCamera(mesh_bounds(*scene_.mesh), scene_.camera,
                             static_cast<float>(scene_.width) / static_cast<float>(scene_.height));
      step_px_ = render_.step;
      overrides_.clear();
      elements_edited_ = false;
      selected_element_ = -1;
      time_ = 0.0;
      make_renderer();
      message_ = "loaded " + scene_.mesh_name;
      return true;
    } catch (const std::exception& e) {
      message_ = std::string("error: ") + e.what();
      std::fprintf(stderr, "ibfvs: %s\n", message_.c_str());
      return false;
    }
  }

  void apply_style(const std::string& name) {
    std::vector<std::string> args = args_;
    const std::vector<std::string> style = style_arguments(name);
    args.insert(args.end(), style.begin(), style.end());  // the preset wins
    if (reload(args)) message_ = "style " + name;
  }

  void load(const std::string& path) {
    if (is_scene_path(path)) {
      try {
        reload(scene_arguments(path));
      } catch (const std::exception& e) {
        message_ = std::string("error: ") + e.what();
      }
      return;
    }
    std::vector<std::string> args = args_;
    args.insert(args.end(), {"--mesh", path});
    reload(args);
  }

  // Flow elements changed: the field is evaluated again and uploaded.
  void elements_changed() {
    FieldSpec& spec = scene_.field_spec;
    if (spec.kind != FieldKind::Elements) {
      spec = FieldSpec::parse("elements");
      message_ = "the field is now the flow elements";
    }
    try {
      for (const FlowElement& e : spec.elements) e.validate();
      scene_.field = evaluate_field(*scene_.mesh, spec, parse_tangent_mode(render_.tangent));
      renderer_->set_field(scene_.field);
      elements_edited_ = true;
      update_dt();
    } catch (const std::exception& e) {
      message_ = std::string("error: ") + e.what();
    }
  }

  // The surface point under the cursor (window coordinates), if any.
  std::optional<glm::vec3> surface_point(glm::vec2 cursor) {
    const ImageF depth = renderer_->read_depth();
    int ww = 0, wh = 0;
    glfwGetWindowSize(window_.handle(), &ww, &wh);
    const int px = static_cast<int>(cursor.x * scene_.width / std::max(ww, 1));
    const int py = scene_.height - 1 - static_cast<int>(cursor.y * scene_.height / std::max(wh, 1));
    if (px < 0 || py < 0 || px >= scene_.width || py >= scene_.height) return std::nullopt;
    const float z = depth.pixels[static_cast<std::size_t>(py) * scene_.width + px];
    if (z >= 1.0f) return std::nullopt;  // background
    const Camera c = camera_.camera();
    const glm::vec4 ndc(2.0f * (px + 0.5f) / scene_.width - 1.0f,
                        2.0f * (py + 0.5f) / scene_.height - 1.0f, 2.0f * z - 1.0f, 1.0f);
    const glm::vec4 world = glm::inverse(c.view_projection()) * ndc;
    return glm::vec3(world) / world.w;
  }

  // The current state rendered offscreen at another size: a renderer of
  // that size runs `frames` frames with the current camera and parameters
  // (the texture needs about 22 to form, section 3.7) and writes its image.
  void snapshot(int width, int height, const std::string& file, int frames = 60) {
    RenderSettings s = renderer_->settings();
    s.width = width;
    s.height = height;
    PreparedScene big = scene_;
    big.settings = s;
    IbfvsRenderer r(s);
    load_scene(r, big, render_);
    ViewerCamera cam = camera_;
    cam.set_aspect(static_cast<float>(width) / static_cast<float>(height));
    const Camera c = cam.camera();
    const float dt = dt_for(c, width, height);  // the same pixels per frame as the window
    for (int k = 0; k < frames; ++k) r.render_frame({c.view(), c.projection()}, dt);
    write_png(r.read_output(), file);
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
      video_ = std::make_unique<VideoWriter>(name, scene_.width, scene_.height, 30.0);
      message_ = std::string("recording ") + name;
    } catch (const std::exception& e) {
      message_ = std::string("error: ") + e.what();
    }
  }

  // Section 3.7: what the texture does while the user drags.
  void begin_drag() {
    dragging_ = true;
    if (drag_mode_ == DragMode::Freeze && !renderer_->locked()) {
      renderer_->lock();
      locked_by_drag_ = true;
    }
    RenderSettings s = renderer_->settings();
    s.advect_view = drag_mode_ == DragMode::Previous ? AdvectView::Previous : AdvectView::Current;
    renderer_->update_settings(s);
  }

  void drag_by(glm::vec2 pixels, bool pan) {
    if (pan)
      camera_.pan(pixels, scene_.height);
    else
      camera_.rotate(pixels);
    if (drag_mode_ == DragMode::Translate) {
      // The paper's option: move F_t and G with the pointer (exact for a pan).
      renderer_->shift_image(pixels);
    }
  }

  void end_drag() {
    dragging_ = false;
    if (locked_by_drag_) {
      renderer_->unlock();
      locked_by_drag_ = false;
    }
    RenderSettings s = renderer_->settings();
    s.advect_view = scene_.settings.advect_view;
    renderer_->update_settings(s);
  }

  void zoom(float steps) {
    camera_.zoom(steps);
    update_dt();
  }

  // The fastest motion back to --step pixels a frame, after a zoom (which
  // would stretch it) or a new field (as render sets dt).
  void update_dt() {
    if (render_.dt > 0.0f) return;  // the user's own dt stays
    const float dt = dt_for(camera_.camera(), scene_.width, scene_.height);
    if (dt > 0.0f) scene_.dt = dt;
  }

  // dt that moves the fastest vertex step_px_ pixels in a width x height image.
  float dt_for(const Camera& c, int width, int height) const {
    return dt_for_pixel_step(scene_.mesh->positions, scene_.field, c.view_projection(), width,
                             height, step_px_);
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
    std::vector<FlowElement>& elements = scene_.field_spec.elements;
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
      drag_mode_ = static_cast<DragMode>((static_cast<int>(drag_mode_) + 1) % 4);
    if (keys.pressed(GLFW_KEY_R)) camera_.reset();
    if (keys.pressed(GLFW_KEY_S)) {
      const std::string name = numbered_name(".png");
      screenshot(name);
    }
    if (keys.pressed(GLFW_KEY_P)) show_panel_ = !show_panel_;
    if (keys.pressed(GLFW_KEY_H)) show_help_ = !show_help_;
  }

  void toggle_lock() {
    if (renderer_->locked())
      renderer_->unlock();
    else
      renderer_->lock();
  }

  void screenshot(const std::string& file) {
    write_png(renderer_->read_output(), file);
    std::printf("ibfvs: wrote %s\n", file.c_str());
  }

  // A parameter by its option name, as the script's `set` and the panel use.
  void set(const std::string& name, const std::string& value) {
    RenderSettings s = renderer_->settings();
    const float v = parse_numbers(name == "background" || name == "surface-color" ? "0" : value,
                                  "set " + name)[0];
    if (name == "alpha") {
      s.alpha = v;
    } else if (name == "beta") {
      s.beta = v;
    } else if (name == "vg") {
      s.noise.rate = v;
    } else if (name == "profile") {
      s.noise.profile = parse_noise_profile(value);
    } else if (name == "background" || name == "surface-color") {
      (name == "background" ? s.background : s.surface_color) = parse_vec3(value, "set " + name);
    } else if (name == "step") {
      if (!(v > 0.0f)) throw InputError("set step: must be a positive number of pixels");
      scene_.dt *= v / step_px_;
      step_px_ = v;
      overrides_[name] = value;
      return;
    } else {
      throw InputError("set: unknown parameter '" + name +
                       "' (alpha, beta, vg, profile, background, surface-color, step)");
    }
    s.validate();
    renderer_->update_settings(s);
    scene_.settings = s;
    overrides_[name] = value;
  }

  std::map<std::string, std::string> overrides_;

  // The render options as given, then every live change, then the camera and
  // the frame count: `ibfvs render SCENE.toml` gives this frame.
  void save_scene(const std::string& file) {
    std::vector<std::string> args;
    for (std::size_t i = 0; i < args_.size(); ++i) {
      // Edited elements replace the field and element options given.
      const std::string name = args_[i].substr(0, args_[i].find('='));
      if (elements_edited_ && (name == "--element" || name == "--field")) {
        if (args_[i].find('=') == std::string::npos) ++i;
        continue;
      }
      args.push_back(args_[i]);
    }
    if (elements_edited_) {
      const glm::vec3 u = scene_.field_spec.value;
      args.insert(args.end(), {"--field", "elements:" + numbers({u.x, u.y, u.z})});
      for (const FlowElement& e : scene_.field_spec.elements)
        args.insert(args.end(),
                    {"--element", numbers({e.a.x, e.a.y, e.a.z, e.b.x, e.b.y, e.b.z, e.rotational,
                                           e.radial, e.tangential, e.core})});
    }
    for (const auto& [name, value] : overrides_) {
      args.push_back("--" + name);
      args.push_back(value);
    }
    const CameraParams& p = camera_.params();
    const float diagonal = std::max(camera_.bounds().diagonal(), 1e-6f);
    char camera[128];
    std::snprintf(camera, sizeof camera, "%.6g,%.6g,%.6g", p.azimuth_deg, p.elevation_deg,
                  p.distance > 0.0f ? camera_.camera().distance_world() / diagonal : 0.0f);
    args.insert(args.end(),
                {"--camera", camera, "--look-at", numbers({p.target.x, p.target.y, p.target.z}),
                 "--frames", std::to_string(renderer_->frame())});
    args.insert(args.end(),
                {"--size", std::to_string(scene_.width) + "x" + std::to_string(scene_.height)});
    std::ofstream out(file);
    out << scene_toml(args);
    if (!out) throw InputError(file + ": cannot write the scene");
    std::printf("ibfvs: saved %s (frame %d)\n", file.c_str(), renderer_->frame());
  }

  void run_script() {
    if (script_drag_.frames_left > 0) {
      drag_by(script_drag_.per_frame, false);
      if (--script_drag_.frames_left == 0) end_drag();
    }
    while (next_action_ < script_.size() && script_[next_action_].frame <= renderer_->frame()) {
      const ScriptAction& a = script_[next_action_++];
      const auto number = [&](std::size_t i) { return parse_numbers(a.args[i], a.verb)[0]; };
      if (a.verb == "drag") {
        begin_drag();
        script_drag_.frames_left = static_cast<int>(number(2));
        script_drag_.per_frame =
            glm::vec2(number(0), number(1)) / static_cast<float>(script_drag_.frames_left);
      } else if (a.verb == "zoom") {
        zoom(number(0));
      } else if (a.verb == "pan") {
        camera_.pan({number(0), number(1)}, scene_.height);
      } else if (a.verb == "set") {
        set(a.args[0], a.args[1]);
      } else if (a.verb == "mode") {
        drag_mode_ = parse_drag_mode(a.args[0]);
      } else if (a.verb == "lock") {
        renderer_->lock();
      } else if (a.verb == "unlock") {
        renderer_->unlock();
      } else if (a.verb == "screenshot") {
        screenshot(a.args[0]);
      } else if (a.verb == "style") {
        apply_style(a.args[0]);
      } else if (a.verb == "load") {
        load(a.args[0]);
      } else if (a.verb == "element") {
        std::vector<FlowElement> kept = scene_.field_spec.elements;
        kept.push_back(FlowElement::parse(a.args[0]));
        if (scene_.field_spec.kind != FieldKind::Elements)
          scene_.field_spec = FieldSpec::parse("elements");
        scene_.field_spec.elements = kept;
        elements_changed();
      } else if (a.verb == "snapshot") {
        const std::vector<float> n = parse_numbers(a.args[0], "snapshot", 2, "W,H");
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
        write_png16(renderer_->read_texture().select_channels(0, 3), a.args[0]);
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
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::Begin("ibfvs", &show_panel_, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::Text("%.1f fps, frame %d, %zu triangles", fps_, renderer_->frame(),
                scene_.mesh->triangle_count());
    RenderSettings s = renderer_->settings();
    bool changed = false;
    changed |= ImGui::SliderFloat("alpha", &s.alpha, 0.0f, 1.0f);
    changed |= ImGui::SliderFloat("beta", &s.beta, 0.0f, 1.0f);
    changed |= ImGui::SliderFloat("v_g", &s.noise.rate, 0.0f, 0.2f);
    int profile = static_cast<int>(s.noise.profile);
    const char* profiles[] = {"square", "sawtooth", "sine", "spike"};
    if (ImGui::Combo("profile", &profile, profiles, 4)) {
      s.noise.profile = parse_noise_profile(profiles[profile]);
      changed = true;
    }
    changed |= ImGui::ColorEdit3("background", &s.background.x);
    changed |= ImGui::ColorEdit3("surface", &s.surface_color.x);
    if (changed) {
      char colour[96];
      overrides_["alpha"] = std::to_string(s.alpha);
      overrides_["beta"] = std::to_string(s.beta);
      overrides_["vg"] = std::to_string(s.noise.rate);
      overrides_["profile"] = profiles[static_cast<int>(s.noise.profile)];
      std::snprintf(colour, sizeof colour, "%g,%g,%g", s.background.r, s.background.g,
                    s.background.b);
      overrides_["background"] = colour;
      std::snprintf(colour, sizeof colour, "%g,%g,%g", s.surface_color.r, s.surface_color.g,
                    s.surface_color.b);
      overrides_["surface-color"] = colour;
      renderer_->update_settings(s);
      scene_.settings = s;
    }
    int mode = static_cast<int>(drag_mode_);
    const char* modes[] = {"plain (a)", "translate (b)", "freeze (c)", "previous (d)"};
    if (ImGui::Combo("drag", &mode, modes, 4)) drag_mode_ = static_cast<DragMode>(mode);
    bool locked = renderer_->locked();
    if (ImGui::Checkbox("lock texture", &locked)) toggle_lock();
    ImGui::SameLine();
    ImGui::Checkbox("pause", &paused_);
    if (ImGui::Button("reset camera")) camera_.reset();
    ImGui::SameLine();
    if (ImGui::Button("restart texture")) renderer_->reset();
    if (scene_.step_count > 1) {
      // Unsteady data (months on the globe): play with pause, step, slide.
      float t = static_cast<float>(time_);
      if (ImGui::SliderFloat("time step", &t, 0.0f,
                             static_cast<float>(scene_.step_count) - 0.01f)) {
        time_ = t;
        player_->seek(time_, *renderer_);
      }
      if (ImGui::Button("<")) time_ = std::floor(time_) - 1.0 + scene_.step_count;
      ImGui::SameLine();
      if (ImGui::Button(">")) time_ = std::floor(time_) + 1.0;
      ImGui::SameLine();
      ImGui::Text("step %d of %zu", static_cast<int>(time_) % static_cast<int>(scene_.step_count),
                  scene_.step_count);
      player_->seek(time_, *renderer_);
    }
    if (ImGui::CollapsingHeader("More parameters")) draw_more_parameters();
    if (ImGui::CollapsingHeader("Styles and files")) draw_styles_and_files();
    if (ImGui::CollapsingHeader("Flow elements")) draw_elements();
    if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
    char path[256];
    std::snprintf(path, sizeof path, "%s", save_path_.c_str());
    if (ImGui::InputText("scene file", path, sizeof path)) save_path_ = path;
    if (ImGui::Button("save scene")) save_scene(save_path_);
    ImGui::SameLine();
    if (ImGui::Button("screenshot")) {
      const std::string name = numbered_name(".png");
      screenshot(name);
    }
    ImGui::SameLine();
    if (ImGui::Button(video_ ? "stop recording" : "record")) toggle_recording();
    ImGui::SetNextItemWidth(120);
    ImGui::InputInt2("##snapshot size", snapshot_size_);
    ImGui::SameLine();
    if (ImGui::Button("render offscreen")) {
      const std::string name = numbered_name(".png");
      try {
        snapshot(std::clamp(snapshot_size_[0], 1, 16384), std::clamp(snapshot_size_[1], 1, 16384),
                 name);
      } catch (const std::exception& e) {
        message_ = std::string("error: ") + e.what();
      }
    }
    ImGui::SameLine();
    if (ImGui::Button("help (h)")) show_help_ = !show_help_;
    ImGui::End();
  }

  // s, step, noise space, tangent mode, colour map and ranges.
  void draw_more_parameters() {
    RenderSettings s = renderer_->settings();
    float scale = s.noise.scale;
    if (ImGui::SliderFloat("s (noise scale)", &scale, 1.0f, 16.0f) && scale != s.noise.scale) {
      scene_.settings.noise.scale = scale;
      overrides_["scale"] = std::to_string(scale);
      make_renderer();  // a new grid: the texture starts again
      return;
    }
    float step = step_px_;
    if (ImGui::SliderFloat("step (px/frame)", &step, 0.25f, 8.0f) && step > 0.0f)
      set("step", std::to_string(step));
    int space = s.object_noise ? 1 : 0;
    const char* spaces[] = {"image (paper)", "object (3.6)"};
    if (ImGui::Combo("noise space", &space, spaces, 2)) {
      s.object_noise = space == 1;
      // s pixels at the distance of the mesh centre, as render does.
      const Camera c = camera_.camera();
      s.object_cell = s.noise.scale * 2.0f * c.distance_world() *
                      std::tan(glm::radians(c.params().fov_deg) * 0.5f) /
                      static_cast<float>(scene_.height);
      overrides_["noise-space"] = space == 1 ? "object" : "image";
      renderer_->update_settings(s);
      scene_.settings = s;
    }
    int tangent = render_.tangent == "3d" ? 1 : 0;
    const char* tangents[] = {"project", "3d"};
    if (ImGui::Combo("tangent", &tangent, tangents, 2)) {
      render_.tangent = tangents[tangent];
      overrides_["tangent"] = render_.tangent;
      try {
        scene_.field =
            evaluate_field(*scene_.mesh, scene_.field_spec, parse_tangent_mode(render_.tangent));
        renderer_->set_field(scene_.field);
      } catch (const std::exception& e) {
        message_ = std::string("error: ") + e.what();
      }
    }
    if (s.use_color) {
      int map = static_cast<int>(s.color_map);
      const char* maps[] = {"viridis", "coolwarm", "grey", "bronze"};
      bool changed = ImGui::Combo("colour map", &map, maps, 4);
      changed |= ImGui::DragFloat2("colour range", &s.color_range.x, 0.01f);
      if (changed) {
        s.color_map = parse_color_map(maps[map]);
        overrides_["color-map"] = maps[map];
        overrides_["color-range"] = numbers({s.color_range.x, s.color_range.y});
        renderer_->update_settings(s);
        scene_.settings = s;
      }
    }
    if (s.use_beta && ImGui::DragFloat2("beta range", &s.beta_range.x, 0.01f)) {
      overrides_["beta-range"] = numbers({s.beta_range.x, s.beta_range.y});
      renderer_->update_settings(s);
      scene_.settings = s;
    }
  }

  void draw_styles_and_files() {
    for (const char* name : {"flow", "particles", "principal", "bronze", "eroded", "topology"}) {
      if (ImGui::Button(name)) apply_style(name);
      ImGui::SameLine();
    }
    ImGui::NewLine();
    char path[512];
    std::snprintf(path, sizeof path, "%s", load_path_.c_str());
    if (ImGui::InputText("mesh or scene", path, sizeof path)) load_path_ = path;
    if (ImGui::Button("load") && !load_path_.empty()) load(load_path_);
  }

  // Add, select, move (ctrl + drag on the surface) and shape flow elements.
  void draw_elements() {
    std::vector<FlowElement>& elements = scene_.field_spec.elements;
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
  add_render_options(cmd, o.render);
  cmd.add_option("--drag", o.drag,
                 "What the texture does while you drag (paper 3.7): plain (fixed on the screen), "
                 "translate (F_t and G move with the pointer), freeze (locked until release), "
                 "previous (advected with the last frame's view: stays on the surface)")
      ->capture_default_str();
  cmd.add_flag("--vsync", o.vsync, "Wait for the display's refresh (default: as fast as it goes)");
  cmd.add_flag("--no-panel", o.no_panel, "Start with the parameter panel hidden (p shows it)");
  cmd.add_option("--script", o.script,
                 "FILE of timed actions (FRAME VERB ARGS per line: drag, zoom, pan, set, mode, "
                 "lock, unlock, screenshot, window, texture, save, style, load, element, record, "
                 "snapshot, help, quit), for tests and demos");
}

std::vector<std::string> render_arguments_of(const std::vector<std::string>& arguments) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    const std::string& a = arguments[i];
    const std::string name = a.substr(0, a.find('='));
    if (name == "--vsync" || name == "--no-panel") continue;
    if (name == "--drag" || name == "--script") {
      if (a.find('=') == std::string::npos) ++i;  // and its value
      continue;
    }
    out.push_back(a);
  }
  return out;
}

int run_view(const ViewOptions& o) {
  parse_drag_mode(o.drag);
  if (!o.script.empty()) read_script(o.script);  // errors before any window
  if (!gl::display_available())
    throw InputError(
        "no display: DISPLAY and WAYLAND_DISPLAY are unset, so ibfvs view cannot open a "
        "window; use ibfvs render for pictures and videos without one");
  PreparedScene scene = prepare_scene(o.render);
  Viewer viewer(o, std::move(scene));
  return viewer.run();
}

}  // namespace ibfvs::app
