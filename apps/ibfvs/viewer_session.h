#pragma once
// The viewer's state and actions without a window: the typed scene in force,
// the session (renderer, field player, frames), the mouse camera, the drag
// behaviours of section 3.7, flow-element editing, recording, saving. The
// window (view_command.cpp), the panel (viewer_panel.h) and the script
// runner (script_runner.h) all act through it; tests drive it in a headless
// context.
//
// Needs a current OpenGL 4.5 context for its whole life.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/render/session.h"
#include "ibfvs/video/video_writer.h"
#include "ibfvs/viewer_state.h"

namespace ibfvs::app {

class ViewerSession {
 public:
  ViewerSession(Scene desc, PreparedScene prepared, DragMode drag);
  ~ViewerSession();
  ViewerSession(const ViewerSession&) = delete;
  ViewerSession& operator=(const ViewerSession&) = delete;

  // ---- frames
  /// One frame: unless paused, the time of an unsteady field moves on and the
  /// texture takes a step seen by the camera (and goes to the recording).
  void frame();
  [[nodiscard]] int frame_count() const { return session_->renderer_frame(); }

  // ---- what is in force
  [[nodiscard]] const Scene& desc() const { return desc_; }
  /// The scene in force, read-only: it changes through the session.
  [[nodiscard]] const PreparedScene& scene() const { return session_->scene(); }
  [[nodiscard]] Session& session() { return *session_; }
  [[nodiscard]] const Session& session() const { return *session_; }
  [[nodiscard]] ViewerCamera& camera() { return camera_; }
  DragMode drag_mode = DragMode::Previous;
  bool paused = false;
  double time = 0.0;          ///< in steps of an unsteady field
  std::string message;        ///< the last note or error, for the panel
  int selected_element = -1;  ///< the flow element the panel and ctrl + drag edit

  // ---- the scene
  /// Takes `desc` through the session (styles, loading, settings that change
  /// the mesh or the field: it prepares the scene again itself). Errors go
  /// to `message`; the old scene stays. Returns whether it took it.
  bool reload(const Scene& desc);
  void apply_style(Style style);
  /// A mesh, or a scene file (*.toml).
  void load(const std::string& path);
  /// Any scene key, by the session's rules (Session::set, key_effect):
  /// texture settings, the step, the noise grid, the tangent mode and the
  /// camera change on the running animation; anything else (and the size,
  /// which is the window's) prepares the scene again, in the session.
  /// Throws SettingError for a bad key or value (nothing changes),
  /// InputError when preparing fails.
  void set(const std::string& key, const std::string& value);
  /// The same for a scene with any keys changed (the panel's).
  void apply_live(const Scene& desc);
  /// The texture from the scene's initial state (Session::restart).
  void restart();
  /// A new noise grid; the texture goes on.
  void set_noise_scale(float scale);
  /// The field evaluated again with `mode`; the texture goes on.
  void set_tangent(TangentMode mode);
  /// The typed scene with the camera, size and frame count of now:
  /// `ibfvs render FILE` gives this frame. Throws InputError.
  void save_scene(const std::filesystem::path& file);

  // ---- flow elements
  void add_element(const FlowElement& element);
  /// The flow elements in force (the field's; none for another field).
  [[nodiscard]] std::vector<FlowElement> elements() const;
  /// The field becomes these flow elements (Session::set_elements), the
  /// typed scene following; errors go to `message`.
  void set_elements(std::vector<FlowElement> elements);

  // ---- mouse (section 3.7)
  void begin_drag();
  /// (dx, dy) pixels, y up: rotate, or pan.
  void drag_by(glm::vec2 pixels, bool pan);
  void end_drag();
  [[nodiscard]] bool dragging() const { return dragging_; }
  void zoom(float steps);
  void pan(glm::vec2 pixels);
  /// The surface point under image pixel (x right, y down from the top), if any.
  [[nodiscard]] std::optional<glm::vec3> surface_point(glm::vec2 pixel);

  // ---- texture and outputs
  void toggle_lock();
  void screenshot(const std::filesystem::path& file);
  void write_texture(const std::filesystem::path& file);
  void toggle_recording();
  [[nodiscard]] bool recording() const { return video_ != nullptr; }
  /// The current state rendered offscreen at another size, `frames` frames
  /// with the current camera (the texture needs about 22 to form).
  void snapshot(int width, int height, const std::filesystem::path& file, int frames = 60);
  /// ibfvs-view-NNNN.EXT in the current folder, numbered on from the last one.
  std::string numbered_name(const char* extension);

 private:
  void update_dt();
  // The viewer's own state after the session prepared the scene again.
  void prepared_again();

  Scene desc_;  // the scene in force, typed: panel, script and loads edit it; save writes it
  std::unique_ptr<Session> session_;
  ViewerCamera camera_;
  bool dragging_ = false, locked_by_drag_ = false;
  int numbered_ = 0;
  std::unique_ptr<VideoWriter> video_;
};

}  // namespace ibfvs::app
