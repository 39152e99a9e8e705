#pragma once
// The viewer's camera under mouse interaction and the drag behaviours of
// section 3.7, needing neither a window nor a GL context.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/support/names.h"

namespace ibfvs::app {

/// What happens to the texture while the user drags (paper section 3.7).
enum class DragMode {
  Plain,      ///< (a) texture fixed in image space: it swims over the moving surface
  Translate,  ///< (b) the paper's fix: F_t and G move with the mouse pointer
  Freeze,     ///< (c) lock the texture during the drag, resume on release
  Previous,   ///< (d) ours: advect with the previous frame's transform (the default)
};
}  // namespace ibfvs::app

template <>
struct ibfvs::EnumNames<ibfvs::app::DragMode> {
  static constexpr EnumName<app::DragMode> table[] = {
      {app::DragMode::Plain, "plain", "the texture stays fixed on the screen (a)"},
      {app::DragMode::Translate, "translate", "F_t and G move with the pointer (b)"},
      {app::DragMode::Freeze, "freeze", "locked until release (c)"},
      {app::DragMode::Previous, "previous", "advected with the last frame's view (d, ours)"},
  };
};

namespace ibfvs::app {

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

}  // namespace ibfvs::app
