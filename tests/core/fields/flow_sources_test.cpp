// Flow sources of paper sections 4.1 and 4.2: potential-flow elements,
// principal-direction fields, gradient flow on height fields.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "ibfvs/core/fields/potential_flow.h"
#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/geometry/curvature.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

TEST(PotentialFlow, RotationalElementCirclesTheLineAndFades) {
  FlowElement e;
  e.a = {0, -1, 0};
  e.b = {0, 1, 0};
  e.rotational = 2.0f;
  float previous = 1e9f;
  for (const float r : {0.2f, 0.4f, 0.8f, 1.6f}) {
    for (const float angle : {0.0f, 1.0f, 2.5f, 4.0f}) {
      const glm::vec3 p(r * std::cos(angle), 0.3f, r * std::sin(angle));
      const glm::vec3 v = e.velocity(p);
      // Tangent to the circle about the Y axis: no radial, no axial part.
      EXPECT_NEAR(glm::dot(v, glm::vec3(p.x, 0, p.z)), 0.0f, 1e-5f);
      EXPECT_NEAR(v.y, 0.0f, 1e-6f);
      // Right-handed about a -> b (+Y): counter-clockwise seen from +Y.
      EXPECT_GT(glm::dot(glm::cross(glm::vec3(0, 1, 0), glm::vec3(p.x, 0, p.z)), v), 0.0f);
      // The 2D point vortex: |v| = S / (2 pi r).
      EXPECT_NEAR(glm::length(v), 2.0f / (2 * 3.14159265f * r), 1e-4f);
    }
    const float speed = glm::length(e.velocity({r, 0, 0}));
    EXPECT_LT(speed, previous);
    previous = speed;
  }
  // On the segment itself: clamped by the core, finite.
  const glm::vec3 on = e.velocity({0, 0.5f, 0});
  EXPECT_TRUE(std::isfinite(on.x + on.y + on.z));
  EXPECT_EQ(glm::length(on), 0.0f);
}

TEST(PotentialFlow, RadialAndTangentialElements) {
  FlowElement source;
  source.a = {-1, 0, 0};
  source.b = {1, 0, 0};
  source.radial = 1.0f;
  const glm::vec3 p(0.2f, 0.5f, 0.0f);
  EXPECT_GT(glm::dot(source.velocity(p), glm::vec3(0, 1, 0)), 0.0f);  // repels
  FlowElement sink = source;
  sink.radial = -1.0f;
  EXPECT_LT(glm::dot(sink.velocity(p), glm::vec3(0, 1, 0)), 0.0f);  // attracts
  FlowElement drag = source;
  drag.radial = 0.0f;
  drag.tangential = 1.0f;
  const glm::vec3 v = drag.velocity(p);
  EXPECT_GT(v.x, 0.0f);
  EXPECT_NEAR(v.y, 0.0f, 1e-6f);
}

TEST(PotentialFlow, SuperpositionIsLinear) {
  const FlowElement a = FlowElement::parse("0,0,0,0,1,0,1.5,-0.5,0.2");
  const FlowElement b = FlowElement::parse("1,0,0,1,0,1,-1,2,0,0.1");
  PotentialFlow flow{{0.3f, 0.0f, -0.1f}, {a, b}};
  for (const glm::vec3& p : {glm::vec3(0.5f, 0.2f, 0.1f), glm::vec3(-1, 2, 3)}) {
    const glm::vec3 sum = glm::vec3(0.3f, 0.0f, -0.1f) + a.velocity(p) + b.velocity(p);
    EXPECT_NEAR(glm::length(flow.velocity(p) - sum), 0.0f, 1e-6f);
  }
  FlowElement twice = a;
  twice.rotational *= 2, twice.radial *= 2, twice.tangential *= 2;
  const glm::vec3 p(0.3f, 0.4f, 0.5f);
  EXPECT_NEAR(glm::length(twice.velocity(p) - 2.0f * a.velocity(p)), 0.0f, 1e-6f);
}

TEST(PotentialFlow, ParseErrors) {
  EXPECT_THROW(FlowElement::parse("0,0,0,0,0,0,1,0,0"), InputError);  // zero length
  EXPECT_THROW(FlowElement::parse("0,0,0,0,1,0,1,0"), InputError);    // 8 numbers
  EXPECT_THROW(FlowElement::parse("0,0,0,0,1,0,1,0,x"), InputError);
  EXPECT_THROW(FlowElement::parse("0,0,0,0,1,0,1,0,0,-1"), InputError);  // negative core
  try {
    FlowElement::parse("0,0,0,0,0,0,1,0,0");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the flow element has zero length in"), std::string::npos);
  }
}

TEST(PotentialFlow, ProjectedOnTheSurfaceIsTangent) {
  TriMesh sphere = make_sphere(1.0f, 24, 48);
  FieldSpec spec = FieldSpec::parse("elements:0.2,0,0");
  spec.elements.push_back(FlowElement::parse("0,-2,0,0,2,0,1,0.5,0.3"));
  const auto v = evaluate_field(sphere, spec, TangentMode::Project);
  float largest = 0.0f;
  for (std::size_t i = 0; i < v.size(); ++i) {
    EXPECT_NEAR(glm::dot(v[i], sphere.normals[i]), 0.0f, 1e-5f);
    largest = std::max(largest, glm::length(v[i]));
  }
  EXPECT_GT(largest, 0.1f);
}

TEST(PrincipalField, CylinderKmaxCirclesTheAxisWithAConsistentSign) {
  const TriMesh cyl = make_cylinder(0.5f, 2.0f, 64, 40);
  const auto v = evaluate_field(cyl, FieldSpec::parse("principal:max:1,0,0"), TangentMode::Project);
  const auto rot =
      evaluate_field(cyl, FieldSpec::parse("principal:max:1,0,0:rot90"), TangentMode::Project);
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (std::abs(cyl.positions[i].y) > 0.9f) continue;  // boundary rings
    EXPECT_NEAR(glm::length(v[i]), 1.0f, 1e-4f);
    EXPECT_NEAR(std::abs(v[i].y), 0.0f, 1e-3f) << i;  // around, not along, the axis
    EXPECT_NEAR(glm::dot(v[i], cyl.normals[i]), 0.0f, 1e-3f);
    // The sign rule: along +X wherever the direction is not perpendicular to it.
    if (std::abs(v[i].x) > 1e-3f) {
      EXPECT_GT(v[i].x, 0.0f) << i;
    }
    // Turned 90 degrees about the normal: along the axis.
    EXPECT_NEAR(std::abs(rot[i].y), 1.0f, 1e-3f) << i;
  }
  const auto vmin = evaluate_field(cyl, FieldSpec::parse("principal:min"), TangentMode::Project);
  for (std::size_t i = 0; i < vmin.size(); ++i) {
    if (std::abs(cyl.positions[i].y) > 0.9f) continue;
    EXPECT_GT(vmin[i].y, 0.999f) << i;  // along the axis, signed along +Y
  }
}

float bump(float x, float y) {
  return std::exp(-4.0f * ((x - 0.2f) * (x - 0.2f) + y * y));
}

TEST(GradientField, DownhillPointsAwayFromTheOnlyMaximum) {
  const TriMesh hill = make_height_field(bump, 1.0f, 64);  // z = bump(x, y), peak at (0.2, 0)
  const auto down =
      evaluate_field(hill, FieldSpec::parse("gradient:down:0,0,1"), TangentMode::Project);
  const auto up =
      evaluate_field(hill, FieldSpec::parse("gradient:up:0,0,1:normalize"), TangentMode::Project);
  std::size_t checked = 0;
  for (std::size_t i = 0; i < down.size(); ++i) {
    const glm::vec2 away(hill.positions[i].x - 0.2f, hill.positions[i].y);
    if (glm::length(away) < 0.05f) continue;  // the summit: no direction
    EXPECT_GT(glm::dot(glm::vec2(down[i]), away), 0.0f) << i;
    EXPECT_LT(down[i].z, 1e-6f);  // downhill
    if (glm::length(up[i]) > 0.0f) {
      EXPECT_NEAR(glm::length(up[i]), 1.0f, 1e-5f);
    }
    ++checked;
  }
  EXPECT_GT(checked, 4000u);
}

TEST(Landscape, BsplineHeightFieldIsSmoothDeterministicAndFacesUp) {
  const auto controls = random_controls(8, 8, 0.3f, 5);
  EXPECT_EQ(controls, random_controls(8, 8, 0.3f, 5));
  EXPECT_NE(controls, random_controls(8, 8, 0.3f, 6));
  const TriMesh m = make_bspline_height_field(controls, 8, 8, 64);
  EXPECT_EQ(m.triangle_count(), 2u * 64 * 64);
  ASSERT_EQ(m.scalars.at("height").size(), m.vertex_count());
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    EXPECT_GT(m.normals[i].y, 0.0f);
    EXPECT_LE(std::abs(m.positions[i].y), 0.3f);  // a convex combination of the controls
    EXPECT_EQ(m.positions[i].y, m.scalars.at("height")[i]);
  }
  // A constant control grid gives a flat plane (the basis sums to one).
  const TriMesh flat = make_bspline_height_field(std::vector<float>(25, 0.1f), 5, 5, 8);
  for (const glm::vec3& p : flat.positions) EXPECT_NEAR(p.y, 0.1f, 1e-6f);
  EXPECT_THROW(make_bspline_height_field(std::vector<float>(9, 0.0f), 3, 3, 8), InputError);
  EXPECT_THROW(make_bspline_height_field(std::vector<float>(15, 0.0f), 4, 4, 8), InputError);
}

// Restless directions (a scan's noise) become coherent: on a cylinder the
// kappa_min line field is the axis; disturbed by up to +-40 degrees with
// random signs, 30 rounds of smoothing bring it back within a few degrees,
// and the exact field stays exact.
TEST(PrincipalField, SmoothingRestoresADisturbedLineField) {
  const TriMesh cyl = make_cylinder(0.5f, 2.0f, 64, 64);
  std::vector<glm::vec3> exact(cyl.vertex_count(), glm::vec3(0, 1, 0)), noisy(exact.size());
  std::uint32_t state = 12345;
  const auto random = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / static_cast<float>(1u << 24);
  };
  for (std::size_t i = 0; i < noisy.size(); ++i) {
    const glm::vec3 side = glm::cross(cyl.normals[i], exact[i]);
    const float a = (random() - 0.5f) * 2.0f * 0.7f;  // +-40 degrees
    noisy[i] = (random() < 0.5f ? -1.0f : 1.0f) * (std::cos(a) * exact[i] + std::sin(a) * side);
  }
  // Mean angle to the axis, in degrees, ignoring the sign.
  const auto error = [&](const std::vector<glm::vec3>& d) {
    double sum = 0;
    for (const glm::vec3& x : d) sum += std::acos(std::min(1.0f, std::abs(x.y))) * 180.0 / M_PI;
    return sum / static_cast<double>(d.size());
  };
  const double before = error(noisy);
  const double after = error(smooth_line_field(cyl, cyl.normals, noisy, 30));
  std::printf("line field on a cylinder: mean error %.2f deg disturbed, %.2f deg after 30 rounds\n",
              before, after);
  EXPECT_GT(before, 15.0);
  EXPECT_LT(after, 3.0);
  EXPECT_LT(error(smooth_line_field(cyl, cyl.normals, exact, 30)), 0.01);
  for (const glm::vec3& x : smooth_line_field(cyl, cyl.normals, noisy, 5))
    EXPECT_NEAR(glm::length(x), 1.0f, 1e-5f);
}

TEST(FieldSpec, ParsesTheNewKinds) {
  const FieldSpec p = FieldSpec::parse("principal:max:0,0,1:rot90");
  EXPECT_EQ(p.kind, FieldKind::Principal);
  EXPECT_TRUE(p.use_max);
  EXPECT_TRUE(p.rotate90);
  EXPECT_EQ(p.value, glm::vec3(0, 0, 1));
  EXPECT_EQ(p.smooth, 0);
  const FieldSpec q = FieldSpec::parse("principal:min:smooth=12:rot90");
  EXPECT_EQ(q.smooth, 12);
  EXPECT_TRUE(q.rotate90);
  EXPECT_NE(q.to_string().find(":smooth=12"), std::string::npos) << q.to_string();
  const FieldSpec g = FieldSpec::parse("gradient:up:normalize");
  EXPECT_FALSE(g.downhill);
  EXPECT_TRUE(g.normalize);
  EXPECT_EQ(g.value, glm::vec3(0, 1, 0));
  EXPECT_EQ(FieldSpec::parse("elements").kind, FieldKind::Elements);
  for (const char* bad :
       {"principal", "principal:mid", "principal:min:0,0,0", "principal:min:spin",
        "principal:min:smooth=", "principal:min:smooth=-1", "principal:min:smooth=2x", "gradient",
        "gradient:sideways", "gradient:down:1,2", "elements:1,2,3:4"})
    EXPECT_THROW(FieldSpec::parse(bad), InputError) << bad;
}

}  // namespace
}  // namespace ibfvs
