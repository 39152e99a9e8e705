#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "ibfvs/core/geometry/displacement.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/scene/camera.h"

namespace ibfvs {
namespace {

TEST(Displacement, OrthographicUniformFieldIsExact) {
  // Ortho over [-1, 1]^2 onto 200 x 100 pixels: 100 px per unit in x, 50 in y.
  const glm::mat4 vp = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, -1.0f, 1.0f);
  const std::vector<glm::vec3> pos = {{0, 0, 0}, {0.5f, 0.5f, 0}};
  EXPECT_NEAR(max_pixel_speed(pos, {{1, 0, 0}, {1, 0, 0}}, vp, 200, 100), 100.0f, 1e-3f);
  EXPECT_NEAR(max_pixel_speed(pos, {{0, 2, 0}, {0, 1, 0}}, vp, 200, 100), 100.0f, 1e-3f);
  EXPECT_NEAR(dt_for_pixel_step(pos, {{1, 0, 0}, {0, 0, 0}}, vp, 200, 100, 3.0f), 0.03f, 1e-6f);
  EXPECT_EQ(dt_for_pixel_step(pos, {{0, 0, 0}, {0, 0, 0}}, vp, 200, 100, 3.0f), 0.0f);
}

// The one rule for dt from the step (the command's fit, the viewer, both
// VTK mappers and ParaView's page): in pixels per unit of time, or from a
// host's world units a pixel; nothing for what does not move or is not a
// number.
TEST(Displacement, DtForStepIsTheOneRule) {
  EXPECT_FLOAT_EQ(dt_for_step(1.5f, 300.0f), 0.005f);
  EXPECT_FLOAT_EQ(dt_for_step(2.0f, 4.0f, 0.01), 0.005f);  // 4 world units: 400 px per unit
  EXPECT_EQ(dt_for_step(1.5f, 0.0f), 0.0f);
  EXPECT_EQ(dt_for_step(0.0f, 300.0f), 0.0f);
  EXPECT_EQ(dt_for_step(1.5f, std::nanf("")), 0.0f);
  EXPECT_EQ(dt_for_step(1.5f, 1e-45f), 0.0f);  // would be infinite
  EXPECT_EQ(dt_for_step(1.5f, 4.0f, 0.0), 0.0f);
  EXPECT_EQ(dt_for_step(1.5f, 4.0f, std::nan("")), 0.0f);
}

TEST(Displacement, PerspectiveStepMatchesFiniteDifference) {
  const TriMesh m = make_sphere(1.0f, 24, 48);
  Camera cam(mesh_bounds(m), {}, 1.0f);
  const glm::mat4 vp = cam.view_projection();
  std::vector<glm::vec3> field(m.vertex_count());
  for (std::size_t i = 0; i < field.size(); ++i)
    field[i] = glm::cross(glm::vec3(0, 1, 0), m.positions[i]);
  const float dt = dt_for_pixel_step(m.positions, field, vp, 512, 512, 2.0f);
  float worst = 0.0f;
  for (std::size_t i = 0; i < field.size(); ++i) {
    const glm::vec2 a = project_to_pixels(vp, m.positions[i], 512, 512);
    const glm::vec2 b = project_to_pixels(vp, m.positions[i] - field[i] * dt, 512, 512);
    worst = std::max(worst, glm::length(a - b));
  }
  EXPECT_NEAR(worst, 2.0f, 0.05f);
}

}  // namespace
}  // namespace ibfvs
