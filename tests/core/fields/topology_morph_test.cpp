// The topology between two steps of a series (topology_morph.h): what
// persists moves from one step's place to the next's, what does not is
// drawn to halfway or from halfway.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "ibfvs/core/fields/topology_morph.h"

namespace ibfvs {
namespace {

TEST(TopologyMorph, AFeatureThatDoesNotPersistIsDrawnToHalfwayOrFromHalfway) {
  // A saddle that goes on (moving), and a node of the first step only, a
  // focus of the second only (a bifurcation), and a line that persists.
  FlowTopology a, b;
  CriticalPoint saddle;
  saddle.kind = CriticalKind::Saddle;
  saddle.id = 0;
  saddle.position = glm::vec3(0.0f);
  CriticalPoint node = saddle;
  node.kind = CriticalKind::AttractingNode;
  node.id = 1;
  node.position = glm::vec3(1.0f, 0.0f, 0.0f);
  a.critical.points = {saddle, node};
  saddle.position = glm::vec3(0.0f, 1.0f, 0.0f);
  CriticalPoint focus = node;
  focus.kind = CriticalKind::RepellingFocus;
  focus.id = 2;
  b.critical.points = {focus, saddle};
  FeatureLine line;
  line.id = 3;
  for (int i = 0; i <= 4; ++i) {
    LinePoint p;
    p.position = glm::vec3(static_cast<float>(i), 0.0f, 0.0f);
    line.points.push_back(p);
  }
  a.lines.lines = {line};
  // The next step's line: twice as long, its points the other way round,
  // and more of them.
  line.points.clear();
  for (int i = 8; i >= 0; --i) {
    LinePoint p;
    p.position = glm::vec3(static_cast<float>(i), 2.0f, 0.0f);
    line.points.push_back(p);
  }
  b.lines.lines = {line};
  const TopologyMorph m = morph_steps(a, b);
  const FlowTopology early = topology_at(m, 0.25f), late = topology_at(m, 0.75f);
  ASSERT_EQ(early.critical.points.size(), 2u);
  ASSERT_EQ(late.critical.points.size(), 2u);
  EXPECT_EQ(early.count(CriticalKind::AttractingNode), 1u);
  EXPECT_EQ(early.count(CriticalKind::RepellingFocus), 0u);
  EXPECT_EQ(late.count(CriticalKind::AttractingNode), 0u);
  EXPECT_EQ(late.count(CriticalKind::RepellingFocus), 1u);
  for (const FlowTopology* t : {&early, &late})
    for (const CriticalPoint& p : t->critical.points)
      if (p.kind == CriticalKind::Saddle) {
        EXPECT_EQ(p.id, 0);
        EXPECT_NEAR(p.position.y, t == &early ? 0.25f : 0.75f, 1e-6f);
      }
  // The line: its ends from (0, 0) and (4, 0) to (0, 2) and (8, 2), as it runs.
  ASSERT_EQ(early.lines.lines.size(), 1u);
  const FeatureLine& l = early.lines.lines[0];
  EXPECT_EQ(l.points.size(), 9u);
  EXPECT_NEAR(glm::length(l.points.front().position - glm::vec3(0.0f, 0.5f, 0.0f)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(l.points.back().position - glm::vec3(5.0f, 0.5f, 0.0f)), 0.0f, 1e-5f);
}

TEST(TopologyMorph, AClosedLineIsPairedFromItsNearestPointTheWayItRuns) {
  // A circle of 12 points, then the same circle of 16 points started
  // elsewhere and run the other way round, 1 higher: halfway, every point
  // half as high, on the circle.
  const auto circle = [](int n, float z, int start, float turn) {
    FeatureLine l;
    l.closed = true;
    l.id = 7;
    for (int i = 0; i < n; ++i) {
      const float t = turn * 6.2831853f * static_cast<float>(i + start) / static_cast<float>(n);
      LinePoint p;
      p.position = glm::vec3(std::cos(t), std::sin(t), z);
      l.points.push_back(p);
    }
    return l;
  };
  FlowTopology a, b;
  a.lines.lines = {circle(12, 0.0f, 0, 1.0f)};
  b.lines.lines = {circle(16, 1.0f, 5, -1.0f)};
  const FlowTopology half = topology_at(morph_steps(a, b), 0.5f);
  ASSERT_EQ(half.lines.lines.size(), 1u);
  EXPECT_TRUE(half.lines.lines[0].closed);
  EXPECT_EQ(half.lines.lines[0].points.size(), 16u);
  for (const LinePoint& p : half.lines.lines[0].points) {
    EXPECT_NEAR(p.position.z, 0.5f, 1e-5f);
    // Paired the wrong way round, points would cut across the circle.
    EXPECT_GT(glm::length(glm::vec2(p.position)), 0.95f);
  }
}

TEST(TopologyMorph, APointMovesAlongTheSurfaceNotThroughIt) {
  // A focus moving 40 degrees along the unit sphere's equator: its straight
  // chord would sink 0.06 below the surface halfway.
  FlowTopology a, b;
  CriticalPoint p;
  p.id = 3;
  p.position = p.normal = glm::vec3(1.0f, 0.0f, 0.0f);
  a.critical.points = {p};
  const float t = 40.0f * 3.14159265f / 180.0f;
  p.position = p.normal = glm::vec3(std::cos(t), std::sin(t), 0.0f);
  b.critical.points = {p};
  const TopologyMorph m = morph_steps(a, b);
  for (const float mix : {0.25f, 0.5f, 0.75f}) {
    const glm::vec3 at = topology_at(m, mix).critical.points.at(0).position;
    EXPECT_NEAR(glm::length(at), 1.0f, 0.002f) << mix;
    EXPECT_NEAR(std::atan2(at.y, at.x), mix * t, 0.02f) << mix;
  }
}

TEST(TopologyMorph, OneStepHeldIsItself) {
  FlowTopology t;
  CriticalPoint p;
  p.position = glm::vec3(1.0f, 2.0f, 3.0f);
  t.critical.points = {p};
  for (const float mix : {0.0f, 0.49f, 0.5f, 1.0f}) {
    const FlowTopology at = topology_at(hold(t), mix);
    ASSERT_EQ(at.critical.points.size(), 1u);
    EXPECT_EQ(at.critical.points[0].position, p.position);
  }
}

}  // namespace
}  // namespace ibfvs
