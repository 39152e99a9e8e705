#pragma once
// Displacement control (paper section 3.3: "care has to be taken that the
// displacement in image space is below a threshold to prevent artifacts").

#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace ibfvs {

/// Largest image-space displacement, in pixels, of T(r_i) - T(r_i - v_i dt)
/// over all vertices, per unit of dt (the derivative at dt = 0, so the result
/// is linear in dt for small steps). Vertices behind the camera are ignored.
float max_pixel_speed(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& field,
                      const glm::mat4& view_projection, int width, int height);

/// The one rule for dt from the step: the time step that moves the fastest
/// point `step` pixels a frame, from its speed in pixels per unit of time
/// (max_pixel_speed). 0 where nothing moves, the step is not positive, or
/// a value is not finite.
[[nodiscard]] float dt_for_step(float step, float pixel_speed);

/// The same for a host's camera (VTK's: ParaView's, PyVista's): from the
/// fastest vector's length in world units and the world units a pixel spans
/// at the focal point.
[[nodiscard]] float dt_for_step(float step, float world_speed, double world_per_pixel);

/// dt such that the largest displacement per frame is `pixels` (0 when the
/// field is zero everywhere).
float dt_for_pixel_step(const std::vector<glm::vec3>& positions,
                        const std::vector<glm::vec3>& field, const glm::mat4& view_projection,
                        int width, int height, float pixels);

}  // namespace ibfvs
