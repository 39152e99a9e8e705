#pragma once
// The viewer's logic that needs no window: the camera under mouse
// interaction, the drag behaviours of section 3.7 and the scripted sessions
// the tests drive the real window with.

#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "ibfvs/core/camera.h"
#include "ibfvs/core/mesh.h"

namespace ibfvs::app {

/// What happens to the texture while the user drags (paper section 3.7).
enum class DragMode {
  Plain,      ///< (a) texture fixed in image space: it swims over the moving surface
  Translate,  ///< (b) the paper's fix: F_t and G move with the mouse pointer
  Freeze,     ///< (c) lock the texture during the drag, resume on release
  Previous,   ///< (d) ours: advect with the previous frame's transform (the default)
};
DragMode parse_drag_mode(const std::string& text);  ///< plain|translate|freeze|previous
std::string to_string(DragMode mode);

/// Orbit camera driven by the mouse: rotate, zoom, pan, reset.
class ViewerCamera {
 public:
  ViewerCamera(const Bounds& bounds, const CameraParams& start, float aspect);

  /// A drag of (dx, dy) pixels, x right and y up: turns the camera about the
  /// centre (0.3 degrees per pixel), the elevation kept within +-89 degrees.
  void rotate(glm::vec2 pixels);
  /// Mouse-wheel steps: each brings the camera 10% closer (negative: away).
  void zoom(float steps);
  /// Moves the look-at point so that the surface at the centre's depth
  /// follows the pointer by (dx, dy) pixels in a window `height` pixels high.
  void pan(glm::vec2 pixels, int height);
  /// Puts the look-at point on `point` (double-click recentring).
  void recentre(const glm::vec3& point);
  void reset();
  void set_aspect(float aspect) { aspect_ = aspect; }

  [[nodiscard]] Camera camera() const { return Camera(bounds_, params_, aspect_); }
  [[nodiscard]] const CameraParams& params() const { return params_; }
  [[nodiscard]] const Bounds& bounds() const { return bounds_; }

 private:
  Bounds bounds_;
  CameraParams start_, params_;
  float aspect_;
};

/// One timed action of a `--script` file.
struct ScriptAction {
  int frame = 0;     ///< the frame before which it happens
  std::string verb;  ///< the action; see read_script
  std::vector<std::string> args;
};

/// Reads a script: one action per line, `FRAME VERB ARGS...`, '#' comments,
/// frames not decreasing. Verbs and their arguments:
///   drag DX DY FRAMES    a mouse drag of DX, DY pixels spread over FRAMES frames
///                        (button down, move, release), through the drag mode
///   zoom STEPS | pan DX DY | set NAME VALUE | mode plain|translate|freeze|previous
///   lock | unlock | screenshot FILE.png (the image) | window FILE.png (with the panel)
///   texture FILE.png (F_t, 16 bits) | save SCENE.toml | style NAME | load MESH|SCENE
///   element AX,AY,AZ,BX,BY,BZ,ROT,RAD,TAN[,CORE] (adds one) | record (toggles MP4)
///   snapshot W,H FILE.png (the current state rendered offscreen at that size)
///   help | quit
/// Throws InputError naming the file and line.
std::vector<ScriptAction> read_script(const std::filesystem::path& path);

}  // namespace ibfvs::app
