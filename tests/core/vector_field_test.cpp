#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibfvs/core/error.h"
#include "ibfvs/core/procedural.h"
#include "ibfvs/core/vector_field.h"

namespace ibfvs {
namespace {

TEST(VectorField, ParsesSpecs) {
  EXPECT_EQ(FieldSpec::parse("file").kind, FieldKind::File);
  const FieldSpec u = FieldSpec::parse("uniform:1,-2.5,3e-1");
  EXPECT_EQ(u.kind, FieldKind::Uniform);
  EXPECT_EQ(u.value, glm::vec3(1, -2.5f, 0.3f));
  EXPECT_EQ(FieldSpec::parse("rotate:0,0,1").kind, FieldKind::Rotate);
  for (const char* bad : {"", "swirl:1,2,3", "uniform", "uniform:1,2", "uniform:1,2,3,4",
                          "uniform:a,b,c", "uniform:1,nan,0", "rotate:0,0,0", "uniform:1,,2"})
    EXPECT_THROW(FieldSpec::parse(bad), InputError) << bad;
  EXPECT_EQ(parse_enum<TangentMode>("3d"), TangentMode::Full3D);
  EXPECT_THROW(parse_enum<TangentMode>("flat"), InputError);
}

TEST(VectorField, RotationAboutTheBoxCentre) {
  TriMesh m = make_torus(1.0f, 0.3f, 32, 12);
  for (glm::vec3& p : m.positions) p += glm::vec3(5, 0, 0);
  const auto v = evaluate_field(m, FieldSpec::parse("rotate:0,2,0"), TangentMode::Full3D);
  for (std::size_t i = 0; i < v.size(); ++i)
    EXPECT_NEAR(
        glm::length(v[i] - glm::cross(glm::vec3(0, 2, 0), m.positions[i] - glm::vec3(5, 0, 0))),
        0.0f, 1e-5f);
}

TEST(VectorField, ProjectionMakesVectorsTangent) {
  const TriMesh m = make_sphere(1.0f, 16, 32);
  FieldReport report;
  const auto v =
      evaluate_field(m, FieldSpec::parse("uniform:0,1,0"), TangentMode::Project, &report);
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_NEAR(glm::dot(v[i], m.normals[i]), 0.0f, 1e-5f);
  EXPECT_NEAR(report.max_magnitude, 1.0f, 1e-3f);
  const auto raw = evaluate_field(m, FieldSpec::parse("uniform:0,1,0"), TangentMode::Full3D);
  for (const glm::vec3& x : raw) EXPECT_EQ(x, glm::vec3(0, 1, 0));
}

TEST(VectorField, NonFiniteVectorsAreZeroedAndCounted) {
  TriMesh m = make_square(1.0f, 2);
  m.vectors.assign(m.vertex_count(), glm::vec3(1, 0, 0));
  m.vectors[2].y = NAN;
  m.vectors[5].z = INFINITY;
  FieldReport report;
  const auto v = evaluate_field(m, FieldSpec::parse("file"), TangentMode::Project, &report);
  EXPECT_EQ(report.non_finite_zeroed, 2u);
  EXPECT_EQ(v[2], glm::vec3(0));
  EXPECT_EQ(v[0], glm::vec3(1, 0, 0));
  for (glm::vec3& x : m.vectors) x = glm::vec3(NAN);
  EXPECT_THROW(evaluate_field(m, FieldSpec::parse("file"), TangentMode::Project), InputError);
  m.vectors.clear();
  EXPECT_THROW(evaluate_field(m, FieldSpec::parse("file"), TangentMode::Project), InputError);
}

}  // namespace
}  // namespace ibfvs
