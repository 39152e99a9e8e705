// A preparation's camera: the height axis and the camera's keys (orient), then
// its pace: dt for the image, the warnings about it and the automatic lock
// frame (pace).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ibfvs/core/geometry/displacement.h"
#include "ibfvs/core/scene/camera.h"
#include "steps.h"

namespace ibfvs::prep {

void orient(Preparation& c) {
  const Scene& s = c.s;
  PreparedScene& p = c.p;
  TriMesh& mesh = *c.mesh;
  std::optional<FieldSpec>& field_spec = c.field_spec;
  const glm::vec3 up = c.up = s.up_auto ? thinnest_axis(mesh) : s.up.value_or(glm::vec3(0, 1, 0));
  p.camera = s.camera;
  p.camera.up = up;
  // A flat surface (one wall patch, a plate) seen edge-on from the default
  // view shows nothing: the default view then looks at its face.
  if (!s.up_auto && !s.up && s.camera.azimuth_deg == 0.0f && s.camera.elevation_deg == 0.0f &&
      s.camera.target == glm::vec3(0.0f)) {
    const Bounds b = mesh_bounds(mesh);
    const glm::vec3 e = b.max - b.min;
    const float largest = std::max({e.x, e.y, e.z});
    if (e.x <= 1e-4f * largest)
      p.camera.azimuth_deg = 90.0f;  // from +X
    else if (e.y <= 1e-4f * largest)
      p.camera.elevation_deg = 90.0f;  // from +Y, down
  }
  if (field_spec && field_spec->kind == FieldKind::Gradient && !field_spec->vector_given)
    field_spec->value = up;
  std::optional<FieldSpec>& default_field = c.default_field;
  default_field = s.default_field;
  if (default_field && default_field->kind == FieldKind::Gradient && !default_field->vector_given)
    default_field->value = up;
  if (s.lock_camera)
    p.lock_camera = CameraParams{s.lock_camera->x,
                                 s.lock_camera->y,
                                 s.lock_camera->z,
                                 s.camera.orthographic,
                                 s.camera.fov_deg,
                                 glm::vec3(0.0f),
                                 up,
                                 std::nullopt};
}

void pace(Preparation& c) {
  const Scene& s = c.s;
  PreparedScene& p = c.p;
  TriMesh& mesh = *c.mesh;
  RenderSettings& settings = p.settings;
  p.mesh = c.mesh;
  const float speed = fit_to_image(p, s.width, s.height);
  const Camera camera(mesh_bounds(mesh), p.camera,
                      static_cast<float>(s.width) / static_cast<float>(s.height));
  if (speed == 0.0f)
    p.warnings.push_back(
        "the field does not move any vertex in the image (zero after projection?); the texture "
        "will stand still");
  char text[200];
  // The display filter bridges gaps up to its length.
  if (p.max_px > settings.noise.scale && p.max_px > settings.filter_length) {
    std::snprintf(text, sizeof text,
                  "the largest displacement is %.1f pixels per frame, more than the noise scale "
                  "%.1f and the filter length %.1f: expect broken streaks (lower step or dt, or "
                  "raise filter)",
                  p.max_px, settings.noise.scale, settings.filter_length);
    p.warnings.push_back(text);
  }

  // ---- the automatic lock: once the texture has had time to cross the mesh
  // as seen (the colours of figure 7 travel from the summits to the basin
  // borders at max_px pixels per frame at most; a path is at most the
  // diagonal of the mesh's image), plus a fifth for slower slopes.
  if (s.lock_at == Scene::kLockAuto) {
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& r : mesh.positions) {
      const glm::vec2 px = project_to_pixels(camera.view_projection(), r, s.width, s.height);
      lo = glm::min(lo, px);
      hi = glm::max(hi, px);
    }
    lo = glm::max(lo, glm::vec2(0.0f));
    hi = glm::min(hi, glm::vec2(static_cast<float>(s.width), static_cast<float>(s.height)));
    const float extent = glm::length(glm::max(hi - lo, glm::vec2(0.0f)));
    p.lock_at = p.max_px > 0.0f ? static_cast<int>(std::ceil(1.2f * extent / p.max_px)) : 0;
    p.lock_at = std::clamp(p.lock_at, 1, 100000);
    if (s.frames == 0) p.frames = p.lock_at + 60;
  }
}

}  // namespace ibfvs::prep
