// Series whose surface moves or changes (scene_prep's StepData): the points
// of each step in the prepared mesh's order, a step with other triangles as
// a mesh of its own, dt from every step played (a run from rest), a host's
// next state of its mesh (prepare_change), and bad steps named in one line.

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "helpers.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

glm::vec3 turned(const glm::vec3& p, float degrees) {
  return glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 0, 1)) *
                   glm::vec4(p, 1.0f));
}

// A square (8 x 8 cells) turning 10 degrees a step about +Z, its vectors a
// swirl that turns with it; still at step 0 (a run from rest). `cells` of a
// step: its own tessellation.
void write_turning_series(const test::TempDir& dir, int steps, int other_step = -1) {
  for (int k = 0; k < steps; ++k) {
    TriMesh m = make_square(1.0f, k == other_step ? 12 : 8);
    for (glm::vec3& p : m.positions) p = turned(p, 10.0f * static_cast<float>(k));
    compute_vertex_normals(m);
    m.vectors.resize(m.vertex_count());
    for (std::size_t i = 0; i < m.vertex_count(); ++i)
      m.vectors[i] = k == 0 ? glm::vec3(0.0f) : glm::vec3(-m.positions[i].y, m.positions[i].x, 0);
    write_ply(m, dir / ("turn_" + std::to_string(k) + ".ply"));
  }
}

TEST(MovingSeries, EachStepsPointsInThePreparedOrder) {
  const test::TempDir dir;
  write_turning_series(dir, 4);
  Scene s;
  s.mesh = (dir / "turn_*.ply").string();
  const PreparedScene p = prepare_scene(s);
  ASSERT_EQ(p.step_count, 4u);
  EXPECT_TRUE(p.step_data(0).positions.empty());  // the prepared mesh's own
  for (std::size_t k = 1; k < 4; ++k) {
    const StepData d = p.step_data(k);
    ASSERT_EQ(d.positions.size(), p.mesh->vertex_count());
    ASSERT_EQ(d.normals.size(), p.mesh->vertex_count());
    EXPECT_EQ(d.mesh, nullptr);
    for (std::size_t i = 0; i < d.positions.size(); ++i) {
      const glm::vec3 expected = turned(p.mesh->positions[i], 10.0f * static_cast<float>(k));
      ASSERT_NEAR(glm::distance(d.positions[i], expected), 0.0f, 1e-5f) << "step " << k;
    }
    // The field on the step's points: the swirl about the origin.
    EXPECT_NEAR(glm::dot(d.field[5], d.positions[5]), 0.0f, 1e-4f);
  }
}

TEST(MovingSeries, DtComesFromTheStepsPlayedNotTheFirst) {
  const test::TempDir dir;
  write_turning_series(dir, 3);
  Scene s;
  s.mesh = (dir / "turn_*.ply").string();
  const PreparedScene normalised = prepare_scene(s);  // step 0 has no flow
  EXPECT_GT(normalised.dt, 0.0f);
  s.image_normalize = false;
  s.step = 2.0f;
  const PreparedScene plain = prepare_scene(s);
  EXPECT_GT(plain.dt, 0.0f);
  EXPECT_NEAR(plain.max_px, 2.0f, 1e-3f);  // the fastest point of any step moves `step` pixels
  for (const std::string& w : plain.warnings) EXPECT_EQ(w.find("stand still"), std::string::npos);
}

TEST(MovingSeries, AStepWithOtherTrianglesIsAMeshOfItsOwn) {
  const test::TempDir dir;
  write_turning_series(dir, 4, 2);
  Scene s;
  s.mesh = (dir / "turn_*.ply").string();
  const PreparedScene p = prepare_scene(s);
  const StepData other = p.step_data(2);
  ASSERT_NE(other.mesh, nullptr);
  EXPECT_EQ(other.mesh->vertex_count(), 13u * 13u);
  EXPECT_EQ(other.field.size(), other.mesh->vertex_count());
  EXPECT_TRUE(other.positions.empty());
  EXPECT_EQ(p.step_data(3).mesh, nullptr);  // and back on the first step's triangles
}

// Prepares the series and reads every step, as a run that plays them all does.
void play_all(const Scene& s) {
  const PreparedScene p = prepare_scene(s);
  for (std::size_t k = 0; k < p.step_count; ++k) (void)p.step_data(k);
}

TEST(MovingSeries, ANonFinitePointOrAMissingArrayNamesTheStep) {
  const test::TempDir dir;
  write_turning_series(dir, 3);
  Scene s;
  s.mesh = (dir / "turn_*.ply").string();
  // Step 2's point 7 is NaN.
  {
    TriMesh m = read_mesh(dir / "turn_2.ply");
    m.positions[7].x = std::numeric_limits<float>::quiet_NaN();
    write_ply(m, dir / "turn_2.ply");
  }
  try {
    play_all(s);
    FAIL() << "a NaN point was taken";
  } catch (const InputError& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_NE(what.find("turn_2.ply"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  // Step 1 without its vectors.
  write_turning_series(dir, 3);
  {
    TriMesh m = read_mesh(dir / "turn_1.ply");
    m.vectors.clear();
    write_ply(m, dir / "turn_1.ply");
  }
  try {
    play_all(s);
    FAIL() << "a step without vectors was taken";
  } catch (const InputError& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_NE(what.find("step 1"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(PrepareChange, TheSameTrianglesTakeThePreparedOrder) {
  Scene s;
  s.field = FieldSpec::parse("file");
  TriMesh given = make_square(1.0f, 10);
  compute_vertex_normals(given);
  given.vectors.assign(given.vertex_count(), glm::vec3(1, 0, 0));
  const PreparedScene p = prepare_scene(s, given, "the input");
  // The next state: points moved up, vectors turned.
  TriMesh next = given;
  for (glm::vec3& r : next.positions) r.z += 0.25f;
  next.vectors.assign(next.vertex_count(), glm::vec3(0, 1, 0));
  const PreparedScene q = prepare_change(p, next, "the input");
  EXPECT_EQ(q.mesh->triangles, p.mesh->triangles);
  for (std::size_t i = 0; i < q.mesh->vertex_count(); ++i) {
    ASSERT_NEAR(q.mesh->positions[i].z, p.mesh->positions[i].z + 0.25f, 1e-6f);
    ASSERT_NEAR(q.mesh->positions[i].x, p.mesh->positions[i].x, 1e-6f);
  }
  EXPECT_NEAR(q.field[3].y, 1.0f, 1e-6f);
  // Other triangles: prepared afresh.
  TriMesh finer = make_square(1.0f, 14);
  compute_vertex_normals(finer);
  finer.vectors.assign(finer.vertex_count(), glm::vec3(1, 0, 0));
  const PreparedScene r = prepare_change(p, finer, "the input");
  EXPECT_EQ(r.mesh->vertex_count(), 15u * 15u);
  EXPECT_EQ(r.field.size(), r.mesh->vertex_count());
}

// A host's states (ParaView's data over its times) are the series its
// files make: the same points at each step, the same own mesh where the
// triangles change, the same field, colours and dt.
TEST(PrepareStates, AHostsStatesAreTheSeriesOfItsFiles) {
  const test::TempDir dir;
  write_turning_series(dir, 4, 2);
  Scene s;
  s.color_by = "x";
  s.color_range = ScalarRange{false, -1.0f, 1.0f};
  Scene files = s;
  files.mesh = (dir / "turn_*.ply").string();
  const PreparedScene from_files = prepare_scene(files);
  std::vector<TriMesh> states;
  for (int k = 0; k < 4; ++k)
    states.push_back(read_mesh(dir / ("turn_" + std::to_string(k) + ".ply")));
  s.field = FieldSpec::parse("file");
  const PreparedScene hosted = prepare_states(s, states, "the host");
  ASSERT_EQ(hosted.step_count, 4u);
  EXPECT_EQ(hosted.mesh->triangles, from_files.mesh->triangles);
  EXPECT_FLOAT_EQ(hosted.dt, from_files.dt);
  for (std::size_t k = 0; k < 4; ++k) {
    const StepData a = hosted.step_data(k), b = from_files.step_data(k);
    EXPECT_EQ(a.positions, b.positions) << "step " << k;
    EXPECT_EQ(a.normals.size(), b.normals.size()) << "step " << k;
    EXPECT_EQ(a.field, b.field) << "step " << k;
    EXPECT_EQ(a.color_scalar, b.color_scalar) << "step " << k;
    ASSERT_EQ(a.mesh == nullptr, b.mesh == nullptr) << "step " << k;
    if (a.mesh) {
      EXPECT_EQ(a.mesh->triangles, b.mesh->triangles) << "step " << k;
    }
  }
  EXPECT_EQ(hosted.step_data(1).positions.size(), hosted.mesh->vertex_count());  // it moves
  EXPECT_NE(hosted.step_data(2).mesh, nullptr);  // its own triangles
  // A bad state is named by its step, in one line.
  states[3].positions[4].y = std::numeric_limits<float>::infinity();
  try {
    (void)prepare_states(s, states, "the host");
    FAIL() << "an infinite point was taken";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the host: step 3"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_THROW((void)prepare_states(s, {}, "the host"), InputError);
}

}  // namespace
}  // namespace ibfvs
