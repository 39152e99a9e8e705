#include "ibfvs/viewer_state.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs::app {

ViewerCamera::ViewerCamera(const Bounds& bounds, const CameraParams& start, float aspect)
    : bounds_(bounds), start_(start), params_(start), aspect_(aspect) {
  Camera check(bounds_, params_, aspect_);  // throws for impossible settings
}

void ViewerCamera::rotate(glm::vec2 pixels) {
  constexpr float kDegreesPerPixel = 0.3f;
  params_.azimuth_deg = std::fmod(params_.azimuth_deg - pixels.x * kDegreesPerPixel, 360.0f);
  params_.elevation_deg =
      std::clamp(params_.elevation_deg - pixels.y * kDegreesPerPixel, -89.0f, 89.0f);
}

void ViewerCamera::zoom(float steps) {
  const float diagonal = std::max(bounds_.diagonal(), 1e-6f);
  // Distance 0 means "fitted": start from the fitted distance.
  const float now = camera().distance_world() / diagonal;
  params_.distance = std::clamp(now * std::pow(0.9f, steps), 0.01f, 100.0f);
}

void ViewerCamera::pan(glm::vec2 pixels, int height) {
  const Camera c = camera();
  const float world_per_pixel = c.world_per_pixel(height);
  const glm::mat4 view = c.view();
  // Rows of the view matrix: the camera's right and up axes in world space.
  const glm::vec3 right(view[0][0], view[1][0], view[2][0]);
  const glm::vec3 up(view[0][1], view[1][1], view[2][1]);
  params_.target -= world_per_pixel * (pixels.x * right + pixels.y * up);
}

void ViewerCamera::recentre(const glm::vec3& point) {
  params_.target = point - bounds_.centre();
}

void ViewerCamera::reset() {
  params_ = start_;
}

}  // namespace ibfvs::app
