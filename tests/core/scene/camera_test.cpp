#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

// True when every vertex projects inside the image.
bool all_inside(const TriMesh& m, const Camera& c, int w, int h) {
  for (const glm::vec3& p : m.positions) {
    const glm::vec2 px = project_to_pixels(c.view_projection(), p, w, h);
    if (px.x < 0 || px.y < 0 || px.x > w || px.y > h) return false;
  }
  return true;
}

TEST(Camera, DefaultLooksFromPlusZAndFitsTheMesh) {
  const TriMesh m = make_torus(1.0f, 0.3f, 48, 16);
  const Bounds b = mesh_bounds(m);
  Camera c(b, {}, 1.0f);
  const glm::vec3 dir = glm::normalize(c.eye() - b.centre());
  EXPECT_NEAR(dir.z, 1.0f, 1e-6f);
  EXPECT_TRUE(all_inside(m, c, 256, 256));
  const glm::vec2 centre = project_to_pixels(c.view_projection(), b.centre(), 256, 256);
  EXPECT_NEAR(centre.x, 128.0f, 1e-3f);
  EXPECT_NEAR(centre.y, 128.0f, 1e-3f);
  // Fitted, not lost in the middle: the torus spans most of the width.
  float min_x = 1e9f, max_x = -1e9f;
  for (const glm::vec3& p : m.positions) {
    const float x = project_to_pixels(c.view_projection(), p, 256, 256).x;
    min_x = std::min(min_x, x);
    max_x = std::max(max_x, x);
  }
  EXPECT_GT(max_x - min_x, 0.8f * 256);
}

TEST(Camera, OrbitAndWideImagesKeepTheMeshInView) {
  const TriMesh m = make_cylinder(0.3f, 2.0f, 32, 8);
  for (const bool ortho : {false, true}) {
    CameraParams p;
    p.orthographic = ortho;
    p.elevation_deg = 20.0f;
    Camera c(mesh_bounds(m), p, 640.0f / 360.0f);
    for (int k = 0; k < 36; ++k) {
      EXPECT_TRUE(all_inside(m, c, 640, 360)) << "ortho " << ortho << " step " << k;
      c.orbit(10.0f);
    }
  }
}

TEST(Camera, AzimuthElevationDistance) {
  const TriMesh m = make_sphere(1.0f, 16, 32);
  CameraParams p;
  p.azimuth_deg = 90.0f;
  p.distance = 3.0f;
  Camera c(mesh_bounds(m), p, 1.0f);
  EXPECT_NEAR(c.eye().x, 3.0f * mesh_bounds(m).diagonal(), 1e-4f);
  p.azimuth_deg = 0.0f;
  p.elevation_deg = 90.0f;  // straight down: the up vector must not degenerate
  Camera top(mesh_bounds(m), p, 1.0f);
  const glm::mat4 v = top.view();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_TRUE(std::isfinite(v[i][j]));
}

// Paper figure 2: every vector moves the image by the same number of pixels,
// whatever its length and its angle to the view; none along the line of sight.
TEST(Camera, ImageNormalizedStepMovesTheGivenPixels) {
  const TriMesh m = make_torus(1.0f, 0.4f, 16, 8);
  CameraParams p;
  p.azimuth_deg = 30.0f;
  p.elevation_deg = 20.0f;
  const Camera camera(mesh_bounds(m), p, 1.5f);
  const glm::mat4 vp = camera.view_projection();
  const int w = 300, h = 200;
  const float probe = 1e-3f * mesh_bounds(m).diagonal();
  double worst = 0.0;
  for (std::size_t i = 0; i < m.vertex_count(); i += 7) {
    const glm::vec3 r = m.positions[i];
    for (const glm::vec3 v : {glm::vec3(0.01f, 0, 0), glm::vec3(0, 5.0f, 0), glm::vec3(3, -1, 2)}) {
      const glm::vec3 d = image_normalized_step(vp, r, v, 3.0f, w, h, probe);
      EXPECT_GT(glm::dot(d, v), 0.0f);  // along v
      const float moved =
          glm::length(project_to_pixels(vp, r, w, h) - project_to_pixels(vp, r - d, w, h));
      worst = std::max(worst, std::abs(static_cast<double>(moved) - 3.0));
    }
  }
  EXPECT_LT(worst, 0.05) << "first-order step off by " << worst << " px";
  EXPECT_EQ(image_normalized_step(vp, m.positions[0], glm::vec3(0), 3.0f, w, h, probe),
            glm::vec3(0));
  // Along the line of sight the image does not move: the step is capped.
  const glm::vec3 eye = camera.eye(), r = m.positions[0];
  const glm::vec3 d = image_normalized_step(vp, r, r - eye, 3.0f, w, h, probe);
  EXPECT_LE(glm::length(d), kImageStepLimit * probe * 1.0001f);
}

// A host's camera (ParaView's view) drawn with its own matrices: the same
// eye, scale at the focal point and orbit as the orbit camera whose matrices
// it was given, in perspective and in parallel projection.
TEST(Camera, AHostsMatricesActAsTheOrbitCameraTheyCameFrom) {
  const TriMesh m = make_torus(1.0f, 0.3f, 48, 16);
  const Bounds b = mesh_bounds(m);
  for (const bool orthographic : {false, true}) {
    CameraParams params;
    params.azimuth_deg = 30.0f;
    params.elevation_deg = 20.0f;
    params.orthographic = orthographic;
    params.target = glm::vec3(0.1f, -0.2f, 0.05f);
    const Camera orbit(b, params, 1.5f);
    CameraParams host;
    host.host = ViewState{orbit.view(), orbit.projection()};
    host.target = params.target;
    const Camera hosted(b, host, 1.0f);  // the aspect is the host's, in its projection
    EXPECT_EQ(hosted.view(), orbit.view());
    EXPECT_EQ(hosted.projection(), orbit.projection());
    EXPECT_LT(glm::length(hosted.eye() - orbit.eye()), 1e-4f);
    EXPECT_NEAR(hosted.distance_world(), orbit.distance_world(), 1e-4f);
    EXPECT_NEAR(hosted.world_per_pixel(300), orbit.world_per_pixel(300),
                1e-4f * orbit.world_per_pixel(300))
        << (orthographic ? "parallel" : "perspective");
    // A quarter turn of the orbit: the eye goes round the focal point alike.
    Camera turned = orbit, host_turned = hosted;
    turned.orbit(90.0f);
    host_turned.orbit(90.0f);
    EXPECT_LT(glm::length(host_turned.eye() - turned.eye()), 1e-3f);
    const glm::vec3 probe(0.3f, 0.2f, -0.1f);
    const glm::vec2 a = project_to_pixels(turned.view_projection(), probe, 300, 200);
    const glm::vec2 c = project_to_pixels(host_turned.view_projection(), probe, 300, 200);
    EXPECT_LT(glm::length(a - c), 0.05f);
  }
}

TEST(Camera, RejectsImpossibleValues) {
  const Bounds b = mesh_bounds(make_square(1.0f, 1));
  CameraParams p;
  p.fov_deg = 0.0f;
  EXPECT_THROW(Camera(b, p, 1.0f), InputError);
  p.fov_deg = 180.0f;
  EXPECT_THROW(Camera(b, p, 1.0f), InputError);
  p = {};
  p.distance = -1.0f;
  EXPECT_THROW(Camera(b, p, 1.0f), InputError);
}

}  // namespace
}  // namespace ibfvs
