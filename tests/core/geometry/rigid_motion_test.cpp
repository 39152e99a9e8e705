// The motion between two saved steps along the rigid motion: a turning body
// keeps its size and its points stay on their circles, a sliding interface
// (two parts that share no point) stays closed, a deforming part blends its
// remainder, and every step's own points are met exactly.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "ibfvs/core/geometry/rigid_motion.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Every point of `mesh` turned by `radians` about the axis through `centre`
// along `axis`, then moved by `slide`.
std::vector<glm::vec3> screwed(const std::vector<glm::vec3>& points, const glm::vec3& axis,
                               const glm::vec3& centre, float radians, const glm::vec3& slide) {
  const glm::mat4 r = glm::rotate(glm::mat4(1.0f), radians, glm::normalize(axis));
  std::vector<glm::vec3> out;
  for (const glm::vec3& p : points)
    out.push_back(glm::vec3(r * glm::vec4(p - centre, 1.0f)) + centre + slide);
  return out;
}

TEST(RigidMotion, ABodyTurningAQuarterKeepsItsSizeOnTheWay) {
  // An ellipsoid-like body (a bumpy sphere) turning 90 degrees about an
  // axis off its centre and sliding along it: every point stays at its
  // distance from the axis, where the chord cuts inside by up to 29%.
  const TriMesh body = make_sphere(1.0f, 16, 32, 0.2f);
  const glm::vec3 axis(0.3f, 1.0f, 0.2f), centre(0.5f, -0.2f, 0.1f), slide = 0.4f * axis;
  const std::vector<glm::vec3> next = screwed(body.positions, axis, centre, 0.5f * kPi, slide);
  const SurfaceMotion motion = fit_surface_motion(body.triangles, body.positions, next);
  EXPECT_EQ(motion.rigid, body.vertex_count());
  float worst = 0.0f, worst_chord = 0.0f;
  for (const float m : {0.25f, 0.5f, 0.75f}) {
    const std::vector<glm::vec3> at = surface_at(body.positions, next, motion, m);
    const std::vector<glm::vec3> truth =
        screwed(body.positions, axis, centre, m * 0.5f * kPi, m * slide);
    const std::vector<glm::vec3> chord = surface_at(body.positions, next, SurfaceMotion{}, m);
    for (std::size_t i = 0; i < at.size(); ++i) {
      worst = std::max(worst, glm::length(at[i] - truth[i]));
      worst_chord = std::max(worst_chord, glm::length(chord[i] - truth[i]));
    }
  }
  EXPECT_LT(worst, 1e-4f);
  EXPECT_GT(worst_chord, 0.2f);  // what the chords did (the shrinking body)
  // The ends are the steps' own points.
  const std::vector<glm::vec3> end = surface_at(body.positions, next, motion, 1.0f);
  for (std::size_t i = 0; i < end.size(); ++i) EXPECT_LT(glm::length(end[i] - next[i]), 1e-5f);
}

TEST(RigidMotion, ASlidingInterfaceStaysClosed) {
  // A disc of two parts that share no point, meeting at radius 0.5: the
  // inner one turns 18 degrees, the outer one stands still. Between steps
  // every inner point stays on its circle (the interface's rim at 0.5);
  // along chords the rim would cut inside by 1.2%, a gap.
  TriMesh rotor = make_square(0.5f, 20), stator = make_square(1.0f, 40);
  // The inner square's points pushed onto a disc, the outer's kept out of it.
  for (glm::vec3& p : rotor.positions) {
    const float r = std::max(std::abs(p.x), std::abs(p.y));
    const float l = glm::length(glm::vec2(p));
    if (l > 0.0f) p = glm::vec3(glm::vec2(p) * (r / l), 0.0f);
  }
  const glm::vec3 z(0, 0, 1);
  const std::vector<glm::vec3> next =
      screwed(rotor.positions, z, glm::vec3(0.0f), 18.0f * kPi / 180.0f, glm::vec3(0.0f));
  TriMesh both = rotor;
  const auto offset = static_cast<std::uint32_t>(rotor.vertex_count());
  both.positions.insert(both.positions.end(), stator.positions.begin(), stator.positions.end());
  for (Triangle t : stator.triangles)
    both.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  std::vector<glm::vec3> both_next = next;
  both_next.insert(both_next.end(), stator.positions.begin(), stator.positions.end());
  const SurfaceMotion motion = fit_surface_motion(both.triangles, both.positions, both_next);
  for (const float m : {0.3f, 0.5f, 0.9f}) {
    const std::vector<glm::vec3> at = surface_at(both.positions, both_next, motion, m);
    for (std::size_t i = 0; i < rotor.vertex_count(); ++i)
      EXPECT_NEAR(glm::length(at[i]), glm::length(rotor.positions[i]), 1e-5f) << i;
    for (std::size_t i = offset; i < at.size(); ++i) EXPECT_EQ(at[i], both.positions[i]);
  }
  // The chord's rim, for the record of what it fixes.
  const std::vector<glm::vec3> chord = surface_at(both.positions, both_next, SurfaceMotion{}, 0.5f);
  float inside = 0.0f;
  for (std::size_t i = 0; i < rotor.vertex_count(); ++i)
    inside = std::max(inside, glm::length(rotor.positions[i]) - glm::length(chord[i]));
  EXPECT_GT(inside, 0.005f);
}

TEST(RigidMotion, NormalsTurnWithTheBodyAndStayUnit) {
  const glm::vec3 omega(0.0f, 0.0f, 0.5f * kPi);
  const glm::vec3 n0(1, 0, 0), n1(0, 1, 0);
  const glm::vec3 half = interpolate_normal(n0, n1, omega, 0.5f);
  EXPECT_NEAR(half.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(half.y, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(glm::length(interpolate_normal(n0, glm::vec3(0, 0, 1), glm::vec3(0.0f), 0.5f)), 1.0f,
              1e-6f);
}

TEST(RigidMotion, ADeformingPartMeetsBothStepsAndBlendsItsRemainder) {
  // A square stretched to twice its width and turned: not rigid; still the
  // ends are the steps' points, and the middle lies between them.
  const TriMesh square = make_square(1.0f, 10);
  std::vector<glm::vec3> stretched;
  for (const glm::vec3& p : square.positions) stretched.push_back({2.0f * p.x, p.y, p.z});
  stretched = screwed(stretched, glm::vec3(0, 0, 1), glm::vec3(0.0f), 0.3f, glm::vec3(0.0f));
  const SurfaceMotion motion = fit_surface_motion(square.triangles, square.positions, stretched);
  EXPECT_LT(motion.rigid, square.vertex_count() / 10);
  const std::vector<glm::vec3> start = surface_at(square.positions, stretched, motion, 0.0f);
  const std::vector<glm::vec3> end = surface_at(square.positions, stretched, motion, 1.0f);
  for (std::size_t i = 0; i < start.size(); ++i) {
    EXPECT_LT(glm::length(start[i] - square.positions[i]), 1e-5f);
    EXPECT_LT(glm::length(end[i] - stretched[i]), 1e-5f);
  }
  const std::vector<glm::vec3> mid = surface_at(square.positions, stretched, motion, 0.5f);
  for (std::size_t i = 0; i < mid.size(); ++i) {
    const float span = glm::length(stretched[i] - square.positions[i]);
    EXPECT_LE(glm::length(mid[i] - 0.5f * (square.positions[i] + stretched[i])),
              0.25f * span + 1e-5f);
  }
}

TEST(RigidMotion, TranslationsLinesAndPointsTakeTheChord) {
  const TriMesh square = make_square(1.0f, 4);
  std::vector<glm::vec3> moved = square.positions;
  for (glm::vec3& p : moved) p += glm::vec3(0.3f, 0.1f, -0.2f);
  const SurfaceMotion still = fit_surface_motion(square.triangles, square.positions, moved);
  for (const glm::vec3& w : still.omega) EXPECT_EQ(w, glm::vec3(0.0f));
  // A triangle whose points lie on a line, and a point in no triangle.
  const std::vector<glm::vec3> line{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {5, 5, 5}};
  const std::vector<glm::vec3> line_next{{0, 0, 0}, {0, 1, 0}, {0, 2, 0}, {6, 5, 5}};
  const std::vector<Triangle> one{{0, 1, 2}};
  const SurfaceMotion flat = fit_surface_motion(one, line, line_next);
  for (const glm::vec3& w : flat.omega) EXPECT_EQ(w, glm::vec3(0.0f));
  EXPECT_EQ(surface_at(line, line_next, flat, 0.5f)[3], glm::vec3(5.5f, 5, 5));
}

TEST(RigidMotion, MismatchedStepsAreRefused) {
  const std::vector<glm::vec3> two(2), three(3);
  EXPECT_THROW(fit_surface_motion(std::vector<Triangle>{}, two, three), InputError);
  EXPECT_THROW(fit_surface_motion(std::vector<Triangle>{{0, 1, 5}}, three, three), InputError);
}

}  // namespace
}  // namespace ibfvs
