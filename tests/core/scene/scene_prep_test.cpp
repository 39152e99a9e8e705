// Scene preparation as a library call: no process, no window, no GL.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibfvs/core/image/image.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / "ibfvs_scene_prep_test";
  fs::create_directories(dir);
  return dir;
}

// Two round hills on a square, height along +Z (as terrain data usually
// comes), 41 x 41 vertices over [-1, 1]^2.
float hills(float x, float y) {
  return 0.3f * std::exp(-((x + 0.5f) * (x + 0.5f) + y * y) / 0.08f) +
         0.3f * std::exp(-((x - 0.5f) * (x - 0.5f) + y * y) / 0.08f);
}

fs::path write_z_terrain() {
  const fs::path p = temp_dir() / "z-terrain.off";
  const int n = 41;
  std::ostringstream out;
  out << "OFF\n" << n * n << " " << 2 * (n - 1) * (n - 1) << " 0\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float x = -1.0f + 2.0f * i / (n - 1), y = -1.0f + 2.0f * j / (n - 1);
      out << x << " " << y << " " << hills(x, y) << "\n";
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i;
      out << "3 " << a << " " << a + 1 << " " << a + n + 1 << "\n";
      out << "3 " << a << " " << a + n + 1 << " " << a + n << "\n";
    }
  std::ofstream(p) << out.str();
  return p;
}

TEST(ScenePrep, DtMovesTheFastestVertexStepPixels) {
  Scene s;
  s.mesh = "torus:1,0.4";
  s.field = FieldSpec::parse("rotate:0,1,0");
  s.width = 200;
  s.height = 100;
  s.step = 2.5f;
  const PreparedScene p = prepare_scene(s);
  EXPECT_EQ(p.width, 200);
  EXPECT_EQ(p.settings.width, 200);
  EXPECT_NEAR(p.max_px, 2.5f, 1e-4f);
  EXPECT_GT(p.dt, 0.0f);
  EXPECT_EQ(p.field.size(), p.mesh->vertex_count());
  EXPECT_EQ(p.mesh_name, "torus:1,0.4");
  EXPECT_TRUE(p.warnings.empty());
}

TEST(ScenePrep, ResizedSharesTheMeshAndKeepsTheStepInPixels) {
  Scene s;
  s.mesh = "torus";
  s.step = 2.0f;
  const PreparedScene p = prepare_scene(s);
  const PreparedScene q = resized(p, 1024, 256);
  EXPECT_EQ(q.mesh.get(), p.mesh.get());  // not read again
  EXPECT_EQ(q.width, 1024);
  EXPECT_EQ(q.settings.height, 256);
  EXPECT_NEAR(q.max_px, 2.0f, 1e-4f);
  EXPECT_NE(q.dt, p.dt);  // a smaller image: more world per pixel
  EXPECT_THROW(resized(p, 0, 10), SettingError);
}

TEST(ScenePrep, RestyledChangesTheLookAndKeepsTheData) {
  Scene s;
  s.mesh = "torus";
  s.field = FieldSpec::parse("rotate:0,1,0");
  s.width = 160;
  s.height = 120;
  const PreparedScene p = prepare_scene(s);
  const std::optional<PreparedScene> crisp = restyled(p, Style::Crisp);
  ASSERT_TRUE(crisp);
  EXPECT_EQ(crisp->mesh.get(), p.mesh.get());  // the same data
  EXPECT_EQ(crisp->settings.filter_length, 24.0f);
  EXPECT_EQ(crisp->scene.style, Style::Crisp);
  const std::optional<PreparedScene> paper = restyled(p, Style::Paper);
  ASSERT_TRUE(paper);
  EXPECT_EQ(paper->settings.noise.scale, 4.0f);
  EXPECT_EQ(paper->settings.image_step, 0.0f);
  EXPECT_EQ(paper->settings.filter_length, 0.0f);
  EXPECT_NEAR(paper->max_px, 3.0f, 1e-4f);  // the paper's step, through dt
  EXPECT_NE(paper->dt, p.dt);
  // A field of its own (the principal directions), curvature colours, random
  // cells and a camera of its own need other data.
  EXPECT_FALSE(restyled(p, Style::Particles));
  EXPECT_FALSE(restyled(p, Style::Principal));
  EXPECT_FALSE(restyled(p, Style::Bronze));
  EXPECT_FALSE(restyled(p, Style::Eroded));
  EXPECT_FALSE(restyled(p, Style::Topology));
  // From the particles style (its field in force), the flow look keeps that
  // field; the principal style signs it otherwise.
  Scene particles = s;
  particles.field.reset();
  apply_style(particles, Style::Particles);
  const PreparedScene q = prepare_scene(particles);
  const std::optional<PreparedScene> flow = restyled(q, Style::Flow);
  ASSERT_TRUE(flow);
  EXPECT_EQ(flow->field, q.field);
  EXPECT_EQ(flow->settings.beta, 0.5f);
  EXPECT_FALSE(restyled(q, Style::Principal));
}

TEST(ScenePrep, ErrorsNameTheKey) {
  const auto key_of = [](Scene s) -> std::string {
    try {
      prepare_scene(s);
    } catch (const SettingError& e) {
      EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
      return e.key();
    }
    return "(none)";
  };
  Scene s;
  s.mesh = "torus";
  s.color_by = "pressure";
  EXPECT_EQ(key_of(s), "color_by");
  s = Scene{};
  s.mesh = "torus:1,2";  // r > R
  EXPECT_EQ(key_of(s), "mesh");
  s = Scene{};
  s.mesh = "torus";
  s.field = FieldSpec::parse("file");
  EXPECT_EQ(key_of(s), "field");
  s = Scene{};
  s.mesh = "torus";
  s.image_normalize = true;
  s.dt = 0.1f;
  EXPECT_EQ(key_of(s), "image_normalize");
  s = Scene{};
  s.mesh = "torus";
  s.surface_image = (temp_dir() / "missing.png").string();
  EXPECT_EQ(key_of(s), "surface_image");
}

TEST(ScenePrep, TheSurfaceImageIsReadOnce) {
  const fs::path png = temp_dir() / "map.png";
  ImageU8 image(4, 2, 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = static_cast<std::uint8_t>(i);
  write_png(image, png);
  Scene s;
  s.mesh = "globe:2";
  s.surface_image = png.string();
  const PreparedScene p = prepare_scene(s);
  fs::remove(png);  // a rebuild or snapshot later must not need the file
  ASSERT_EQ(p.surface_image.width, 4);
  ASSERT_EQ(p.surface_image.height, 2);
  const int c = p.surface_image.channels;
  ASSERT_GE(c, 3);
  for (std::size_t i = 0; i < 8; ++i)
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_EQ(p.surface_image.pixels[i * c + k], image.pixels[i * 3 + k]);
}

TEST(ScenePrep, TopologyLooksDownTheMeshsOwnHeightAxis) {
  Scene s;
  s.mesh = write_z_terrain().string();
  apply_style(s, Style::Topology);
  const PreparedScene p = prepare_scene(s);
  // +Z is the terrain's thinnest axis: the camera's vertical and the
  // gradient's axis.
  EXPECT_EQ(p.camera.up, glm::vec3(0, 0, 1));
  EXPECT_EQ(p.field_spec.value, glm::vec3(0, 0, 1));
  const Camera camera(mesh_bounds(*p.mesh), p.camera, 1.0f);
  const glm::vec3 view_dir = glm::normalize(mesh_bounds(*p.mesh).centre() - camera.eye());
  EXPECT_LT(view_dir.z, -0.999f) << "not looking straight down +Z";
  // The field runs downhill wherever the slope is steep enough to tell.
  std::size_t checked = 0;
  for (std::size_t i = 0; i < p.mesh->vertex_count(); ++i) {
    const glm::vec3 r = p.mesh->positions[i];
    const float e = 1e-3f;
    const glm::vec2 grad((hills(r.x + e, r.y) - hills(r.x - e, r.y)) / (2 * e),
                         (hills(r.x, r.y + e) - hills(r.x, r.y - e)) / (2 * e));
    if (glm::length(grad) < 0.05f) continue;
    ++checked;
    EXPECT_LT(glm::dot(glm::vec2(p.field[i]), grad), 0.0f) << "uphill at vertex " << i;
  }
  EXPECT_GT(checked, 200u);
  // The lock waits until colours can cross the mesh's image at max_px per
  // frame (512 pixels across at 3 px/frame: more than 170 frames, not 40).
  EXPECT_GT(p.lock_at, 150);
  EXPECT_EQ(p.frames, p.lock_at + 60);
  ASSERT_TRUE(p.lock_camera);
  EXPECT_EQ(p.lock_camera->up, glm::vec3(0, 0, 1));
}

TEST(ScenePrep, UpStaysYForMeshesWithoutOne) {
  Scene s;
  s.mesh = "torus";
  const PreparedScene p = prepare_scene(s);
  EXPECT_EQ(p.camera.up, glm::vec3(0, 1, 0));
  // The default camera: from +Z, +Y up, as before the height axis existed.
  const Camera camera(mesh_bounds(*p.mesh), p.camera, 1.0f);
  EXPECT_GT(camera.eye().z, 0.0f);
  EXPECT_NEAR(camera.eye().x, 0.0f, 1e-5f);
}

}  // namespace
}  // namespace ibfvs

namespace ibfvs {
namespace {

// Three PLY files step_1.ply .. step_10.ply (numbers, not text, order them)
// of one triangle, vectors (k, 0, 0).
fs::path write_ply_series() {
  const fs::path dir = temp_dir() / "series";
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const int k : {1, 2, 10}) {
    TriMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.triangles = {{0, 1, 2}};
    compute_vertex_normals(m);
    m.vectors.assign(3, glm::vec3(static_cast<float>(k), 0, 0));
    write_ply(m, dir / ("step_" + std::to_string(k) + ".ply"));
  }
  return dir;
}

TEST(ScenePrep, NumberedFilesAreTheStepsOfAnUnsteadyField) {
  const fs::path dir = write_ply_series();
  Scene s;
  s.mesh = (dir / "step_*.ply").string();
  const PreparedScene p = prepare_scene(s);
  ASSERT_EQ(p.step_count, 3u);
  EXPECT_FLOAT_EQ(p.step_data(1).field[0].x, 2.0f);
  EXPECT_FLOAT_EQ(p.step_data(2).field[0].x, 10.0f);  // step_10 after step_2
  // One step by the time key, reversed.
  s.time = TimeRange::parse("2");
  s.reverse = true;
  const PreparedScene one = prepare_scene(s);
  EXPECT_EQ(one.step_count, 1u);
  EXPECT_FLOAT_EQ(one.field[0].x, -10.0f);
  s.time = TimeRange::parse("0:3");
  try {
    prepare_scene(s);
    FAIL();
  } catch (const SettingError& e) {
    EXPECT_NE(std::string(e.what()).find("has 3 steps (0..2), asked for 0:3"), std::string::npos)
        << e.what();
  }
  s.mesh = (dir / "nothing_*.ply").string();
  s.time.reset();
  EXPECT_THROW(prepare_scene(s), InputError);
}

TEST(ScenePrep, DatasetsWithoutTheVtkLibrarySayHowToGetThem) {
  // The core tests do not install ibfvs::vtk: a .vtp is refused in one line.
  Scene s;
  s.mesh = "wing.vtp";
  try {
    prepare_scene(s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wing.vtp: VTK and OpenFOAM files need ibfvs built with "
                                         "ParaView's VTK (Debian's paraview-dev)"),
              std::string::npos)
        << e.what();
  }
}

TEST(ScenePrep, ReverseNegatesASteadyField) {
  Scene s;
  s.mesh = "torus";
  s.field = FieldSpec::parse("rotate:0,1,0");
  const PreparedScene a = prepare_scene(s);
  s.reverse = true;
  const PreparedScene b = prepare_scene(s);
  for (std::size_t i = 0; i < a.field.size(); i += 97) EXPECT_EQ(a.field[i], -b.field[i]);
}

}  // namespace
}  // namespace ibfvs
