#pragma once
// What the renderer's GL tests share: the fixture, a flat view and a sphere
// scene with its field and camera.

#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gl_fixture.h"
#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/geometry/displacement.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/render/ibfvs_renderer.h"

namespace ibfvs::rendertest {

class RendererGLTest : public test::GlTest {};

// A unit ortho view of the square [-1, 1]^2 in the plane z = 0.
inline ViewState flat_view() {
  return {glm::mat4(1.0f), glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, -1.0f, 1.0f)};
}

// The settings the comparisons with the CPU reference run at: coarse noise
// (5 px), a slow smooth profile, alpha 0.12.
inline RenderSettings reference_settings(int w, int h, NoiseProfile profile = NoiseProfile::Sine) {
  RenderSettings settings;
  settings.width = w;
  settings.height = h;
  settings.alpha = 0.12f;
  settings.noise.scale = 5.0f;
  settings.noise.profile = profile;
  settings.noise.rate = 0.03f;
  return settings;
}

struct Scene {
  TriMesh mesh;
  std::vector<glm::vec3> field;
  Camera camera;
};

inline Scene sphere_scene(const std::string& field, TangentMode mode, float aspect = 1.0f) {
  TriMesh m = make_sphere(1.0f, 96, 192, 0.06f);
  std::vector<glm::vec3> f = evaluate_field(m, FieldSpec::parse(field), mode);
  Camera c(mesh_bounds(m), {}, aspect);
  return {std::move(m), std::move(f), std::move(c)};
}

inline float step_dt(const Scene& s, int w, int h, float pixels) {
  return dt_for_pixel_step(s.mesh.positions, s.field, s.camera.view_projection(), w, h, pixels);
}

/// The surface point under pixel (x, y) of a w x h image at window depth d,
/// given the inverse of the view-projection that drew it.
inline glm::vec3 unproject_pixel(const glm::mat4& inverse, int x, int y, float d, int w, int h) {
  const glm::vec4 p =
      inverse * glm::vec4(2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(w) - 1.0f,
                          2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(h) - 1.0f,
                          2.0f * d - 1.0f, 1.0f);
  return glm::vec3(p) / p.w;
}

}  // namespace ibfvs::rendertest
