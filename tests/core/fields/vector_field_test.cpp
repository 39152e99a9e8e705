#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/support/error.h"

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

namespace ibfvs {
namespace {

TEST(VectorField, FileArraysByName) {
  EXPECT_EQ(FieldSpec::parse("file:wallShearStress").array, "wallShearStress");
  EXPECT_EQ(FieldSpec::parse("file:wallShearStress").text(), "file:wallShearStress");
  EXPECT_EQ(FieldSpec::parse("file").array, "");
  const FieldSpec s = FieldSpec::parse("sample:case.foam:U:0.002");
  EXPECT_EQ(s.kind, FieldKind::Sample);
  EXPECT_EQ(s.path, "case.foam");
  EXPECT_EQ(s.array, "U");
  EXPECT_FLOAT_EQ(s.offset, 0.002f);
  EXPECT_EQ(FieldSpec::parse(s.text()).offset, s.offset);
  EXPECT_THROW(FieldSpec::parse("sample:case.foam"), InputError);
  EXPECT_THROW(FieldSpec::parse("sample:a:U:x"), InputError);

  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}};
  compute_vertex_normals(m);
  m.vector_arrays["U"] = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}};
  m.scalars["p"] = {1, 2, 3};
  m.other_arrays["T"] = 9;
  // The only vector array needs no name; a scalar or a tensor says why not.
  EXPECT_EQ(evaluate_field(m, FieldSpec::parse("file"), TangentMode::Project)[0],
            glm::vec3(1, 0, 0));
  const auto message = [&](const char* spec) {
    try {
      evaluate_field(m, FieldSpec::parse(spec), TangentMode::Project);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("file:p"), "file:p: the array has 1 component; a field needs 3");
  EXPECT_EQ(message("file:T"), "file:T: the array has 9 components; a field needs 3");
  EXPECT_EQ(message("file:V"), "file:V: no such array (arrays: U (3), p (1), T (9))");
  m.vector_arrays["W"] = m.vector_arrays["U"];
  EXPECT_EQ(message("file"),
            "file: the mesh has 2 vector arrays; name one with file:NAME (arrays: U (3), W (3), "
            "p (1), T (9))");
}

}  // namespace
}  // namespace ibfvs
