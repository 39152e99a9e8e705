#include "ibfvs/core/geometry/displacement.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace ibfvs {

float max_pixel_speed(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& field,
                      const glm::mat4& vp, int width, int height) {
  // d/dt of the projection: J(r) v, with J the Jacobian of x' = T(r) in pixels.
  float best = 0.0f;
  const float sx = 0.5f * static_cast<float>(width), sy = 0.5f * static_cast<float>(height);
  const std::size_t n = std::min(positions.size(), field.size());
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec4 c = vp * glm::vec4(positions[i], 1.0f);
    if (!(c.w > 1e-12f)) continue;
    const glm::vec4 d = vp * glm::vec4(field[i], 0.0f);
    const float dx = (d.x * c.w - c.x * d.w) / (c.w * c.w) * sx;
    const float dy = (d.y * c.w - c.y * d.w) / (c.w * c.w) * sy;
    const float speed = std::sqrt(dx * dx + dy * dy);
    if (std::isfinite(speed)) best = std::max(best, speed);
  }
  return best;
}

float dt_for_step(float step, float pixel_speed) {
  if (!(step > 0.0f) || !(pixel_speed > 0.0f)) return 0.0f;
  const float dt = step / pixel_speed;
  return std::isfinite(dt) ? dt : 0.0f;
}

float dt_for_step(float step, float world_speed, double world_per_pixel) {
  if (!(world_per_pixel > 0.0) || !std::isfinite(world_per_pixel)) return 0.0f;
  // Pixels a unit of time at the focal point: world units over world units a pixel.
  return dt_for_step(step, static_cast<float>(world_speed / world_per_pixel));
}

float dt_for_pixel_step(const std::vector<glm::vec3>& positions,
                        const std::vector<glm::vec3>& field, const glm::mat4& vp, int width,
                        int height, float pixels) {
  return dt_for_step(pixels, max_pixel_speed(positions, field, vp, width, height));
}

}  // namespace ibfvs
