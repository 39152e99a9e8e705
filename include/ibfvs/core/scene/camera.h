#pragma once
// The view transform T of the paper (modelling, viewing and projection):
// an orbit camera around the centre of the mesh's bounding box.

#include <optional>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// One camera state: the matrices a frame is drawn with, world to eye and
/// eye to clip, in OpenGL's conventions (ibfvs's own camera's, or a host
/// application's: ParaView's view, PyVista's plotter).
struct ViewState {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
};

/// World units a pixel spans `focal_distance` in front of a camera with
/// `projection` (perspective; anywhere for a parallel projection), in an
/// image `height` pixels high: the one rule for a host's camera (the VTK
/// mappers' dt, Camera::world_per_pixel of a host's view).
[[nodiscard]] double world_per_pixel(const glm::mat4& projection, double focal_distance,
                                     int height);

/// Camera settings. The default looks at the centre of the bounding box from
/// +Z with +Y up and fits the whole mesh in the image.
struct CameraParams {
  float azimuth_deg = 0.0f;        ///< rotation about +Y; 90 looks from +X
  float elevation_deg = 0.0f;      ///< above the XZ plane; 90 looks down from +Y
  float distance = 0.0f;           ///< in bounding-box diagonals; 0 fits the mesh
  bool orthographic = false;       ///< orthographic instead of perspective
  float fov_deg = 30.0f;           ///< vertical field of view (perspective)
  glm::vec3 target{0.0f};          ///< look-at point minus the box centre (panning), world units
  glm::vec3 up{0.0f, 1.0f, 0.0f};  ///< the vertical: azimuth turns about it, elevation rises
                                   ///< along it (+Y by default; +Z for a terrain in z = h(x, y))
  /// A host's camera: its matrices in place of the orbit camera's (azimuth,
  /// elevation, distance, framing and depth range; the aspect is the
  /// host's). `target` then is its focal point minus the box centre, and an
  /// orbit turns its view about the vertical through that point.
  std::optional<ViewState> host;
};

/// Position and projection for one frame.
class Camera {
 public:
  /// Throws InputError for an impossible field of view or distance.
  Camera(const Bounds& bounds, const CameraParams& params, float aspect);

  /// Turns the camera about the vertical axis through the centre (the paper's
  /// "rotating object", seen from the object).
  void orbit(float degrees) { params_.azimuth_deg += degrees; }
  /// A new image shape (width / height), the same view.
  void set_aspect(float aspect) { aspect_ = aspect; }

  [[nodiscard]] glm::mat4 view() const;
  [[nodiscard]] glm::mat4 projection() const;
  [[nodiscard]] glm::mat4 view_projection() const { return projection() * view(); }
  [[nodiscard]] glm::vec3 eye() const;
  [[nodiscard]] const CameraParams& params() const { return params_; }
  /// Distance from the eye to the centre, in world units.
  [[nodiscard]] float distance_world() const;
  /// World units a pixel spans at the centre's depth, in an image `height`
  /// pixels high (perspective, and the orthographic view's same framing).
  [[nodiscard]] float world_per_pixel(int height) const;

 private:
  Bounds bounds_;
  CameraParams params_;
  float aspect_ = 1.0f;
};

/// Projects a world point with a view-projection matrix to pixel coordinates
/// (origin at the lower left, pixel centres at +0.5), as the GPU does.
glm::vec2 project_to_pixels(const glm::mat4& view_projection, const glm::vec3& p, int width,
                            int height);

/// Image-space normalisation (paper figure 2, "the flow is normalized in image
/// space"): the displacement along v, in world units, whose projection moves
/// the image of r by `pixels` pixels, to first order. The image motion of a
/// probe step of `probe` world units along v sets the scale. At most
/// kImageStepLimit probes long (v almost along the line of sight); zero where
/// v is zero, has no image motion, or r is behind the eye. The GPU's vertex
/// shader computes the same per vertex.
inline constexpr float kImageStepLimit = 50.0f;
glm::vec3 image_normalized_step(const glm::mat4& view_projection, const glm::vec3& r,
                                const glm::vec3& v, float pixels, int width, int height,
                                float probe);

}  // namespace ibfvs
