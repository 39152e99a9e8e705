#include "ibfvs/core/scene/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include "ibfvs/core/support/error.h"

namespace ibfvs {

Camera::Camera(const Bounds& bounds, const CameraParams& params, float aspect)
    : bounds_(bounds), params_(params), aspect_(aspect) {
  if (!(params.fov_deg > 0.0f && params.fov_deg < 180.0f))
    throw SettingError("fov", "the field of view must be between 0 and 180 degrees");
  if (!(params.distance >= 0.0f) || !std::isfinite(params.distance))
    throw SettingError("camera", "the distance must be a positive number of diagonals");
  if (!(aspect > 0.0f)) throw InputError("camera: the aspect ratio must be positive");
}

float Camera::distance_world() const {
  if (params_.host) return glm::length(eye() - (bounds_.centre() + params_.target));
  const float diag = std::max(bounds_.diagonal(), 1e-6f);
  if (params_.distance > 0.0f) return params_.distance * diag;
  // Fit the sphere about the box centre that holds every vertex in the
  // narrower field of view, with 3% margin. A sphere, not the box, so that an
  // orbiting camera keeps the whole mesh in view at a constant distance.
  const float radius = bounds_.radius > 0.0f ? bounds_.radius : 0.5f * diag;
  const float half_v = glm::radians(params_.fov_deg) * 0.5f;
  const float half_h = std::atan(std::tan(half_v) * aspect_);
  return 1.03f * radius / std::sin(std::min(half_v, half_h));
}

double world_per_pixel(const glm::mat4& p, double focal_distance, int height) {
  // Half the image's height at the focal point's depth: 1 / P[1][1] of the
  // projection, times that depth in perspective (P[3][3] is 0).
  const double half = (p[3][3] == 0.0f ? focal_distance : 1.0) / static_cast<double>(p[1][1]);
  return 2.0 * std::abs(half) / static_cast<double>(std::max(height, 1));
}

float Camera::world_per_pixel(int height) const {
  if (const std::optional<ViewState>& host = params_.host)
    return static_cast<float>(ibfvs::world_per_pixel(host->projection, distance_world(), height));
  return 2.0f * distance_world() * std::tan(glm::radians(params_.fov_deg) * 0.5f) /
         static_cast<float>(std::max(height, 1));
}

namespace {

// The rotation that takes +Y to `up` (the identity for +Y), so that azimuth
// and elevation keep their meaning about any vertical.
glm::mat3 up_frame(const glm::vec3& up) {
  const float len = glm::length(up);
  const glm::vec3 u = len > 0.0f ? up / len : glm::vec3(0, 1, 0);
  const float c = u.y;
  if (c > 0.999999f) return glm::mat3(1.0f);
  if (c < -0.999999f)
    return glm::mat3(glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, -1));
  const glm::vec3 axis = glm::normalize(glm::cross(glm::vec3(0, 1, 0), u));
  return glm::mat3(glm::rotate(glm::mat4(1.0f), std::acos(c), axis));
}

}  // namespace

glm::vec3 Camera::eye() const {
  if (params_.host) return glm::vec3(glm::inverse(view())[3]);
  const float az = glm::radians(params_.azimuth_deg);
  const float el = glm::radians(params_.elevation_deg);
  const glm::vec3 dir(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
  return bounds_.centre() + params_.target + distance_world() * (up_frame(params_.up) * dir);
}

glm::mat4 Camera::view() const {
  if (const std::optional<ViewState>& host = params_.host) {
    if (params_.azimuth_deg == 0.0f) return host->view;
    // An orbit: the world turned about the vertical through the focal point.
    const glm::vec3 pivot = bounds_.centre() + params_.target;
    const float len = glm::length(params_.up);
    const glm::vec3 up = len > 0.0f ? params_.up / len : glm::vec3(0, 1, 0);
    return host->view * glm::translate(glm::mat4(1.0f), pivot) *
           glm::rotate(glm::mat4(1.0f), -glm::radians(params_.azimuth_deg), up) *
           glm::translate(glm::mat4(1.0f), -pivot);
  }
  const glm::vec3 eye_pos = eye();
  const glm::vec3 look_at = bounds_.centre() + params_.target;
  const glm::vec3 forward = glm::normalize(look_at - eye_pos);
  // Looking straight up or down: the vertical is degenerate, take the
  // azimuth direction.
  const glm::mat3 frame = up_frame(params_.up);
  glm::vec3 up = frame[1];
  if (std::abs(glm::dot(forward, up)) > 0.999f) {
    const float az = glm::radians(params_.azimuth_deg);
    up = frame * glm::vec3(-std::sin(az), 0, -std::cos(az)) *
         (glm::dot(forward, frame[1]) < 0 ? 1.0f : -1.0f);
  }
  return glm::lookAt(eye_pos, look_at, up);
}

glm::mat4 Camera::projection() const {
  if (params_.host) return params_.host->projection;
  const float diag = std::max(bounds_.diagonal(), 1e-6f);
  const float radius = bounds_.radius > 0.0f ? bounds_.radius : 0.5f * diag;
  const float dist = distance_world();
  // The mesh lies within radius of the centre, which panning moves off the axis.
  const float reach = 1.5f * radius + glm::length(params_.target);
  const float far_plane = dist + reach;
  const float near_plane = std::max(dist - reach, 1e-3f * radius);
  if (params_.orthographic) {
    // The same framing as the fitted perspective view at the centre's depth.
    const float half_h = dist * std::tan(glm::radians(params_.fov_deg) * 0.5f);
    const float half_w = half_h * aspect_;
    return glm::ortho(-half_w, half_w, -half_h, half_h, near_plane, far_plane);
  }
  return glm::perspective(glm::radians(params_.fov_deg), aspect_, near_plane, far_plane);
}

glm::vec2 project_to_pixels(const glm::mat4& vp, const glm::vec3& p, int width, int height) {
  const glm::vec4 c = vp * glm::vec4(p, 1.0f);
  const float w = std::max(c.w, 1e-12f);
  return {(c.x / w * 0.5f + 0.5f) * static_cast<float>(width),
          (c.y / w * 0.5f + 0.5f) * static_cast<float>(height)};
}

glm::vec3 image_normalized_step(const glm::mat4& vp, const glm::vec3& r, const glm::vec3& v,
                                float pixels, int width, int height, float probe) {
  const float speed = glm::length(v);
  if (!(speed > 0.0f) || !(probe > 0.0f)) return glm::vec3(0.0f);
  const glm::vec3 u = v / speed;
  const glm::vec4 a = vp * glm::vec4(r, 1.0f);
  const glm::vec4 b = vp * glm::vec4(r - u * probe, 1.0f);
  if (a.w <= 1e-6f || b.w <= 1e-6f) return glm::vec3(0.0f);
  const glm::vec2 moved = (glm::vec2(a) / a.w - glm::vec2(b) / b.w) * 0.5f *
                          glm::vec2(static_cast<float>(width), static_cast<float>(height));
  const float length = glm::length(moved);
  if (!(length > 0.0f)) return glm::vec3(0.0f);
  // Nearly along the line of sight the world step would grow without bound:
  // at most kImageStepLimit probes.
  return u * (probe * std::min(pixels / length, kImageStepLimit));
}

}  // namespace ibfvs
