#include "ibfvs/core/texture/display.h"

#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

namespace ibfvs {
namespace {

// The tap texture's 8-bit channels (display.h): what the GPU stores and
// ReferenceIbfvs models.

TEST(TapTexture, DepthMapSpansTheNearAndFarPlanes) {
  const glm::vec2 perspective = tap_depth_map(glm::perspective(0.6f, 1.3f, 0.5f, 20.0f));
  EXPECT_NEAR(perspective.x, std::log(0.5f), 1e-4f);
  EXPECT_NEAR(1.0f / perspective.y, std::log(40.0f), 1e-3f);
  EXPECT_FLOAT_EQ(encode_tap_depth(0.5f, perspective), 1.0f / 255.0f);
  EXPECT_NEAR(encode_tap_depth(20.0f, perspective), 1.0f, 1e-5f);
  EXPECT_FLOAT_EQ(encode_tap_depth(0.01f, perspective), 1.0f / 255.0f);  // clamped, never 0
  const glm::vec2 ortho = tap_depth_map(glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 1.0f, 11.0f));
  EXPECT_NEAR(ortho.x, 0.0f, 1e-5f);
  EXPECT_NEAR(1.0f / ortho.y, std::log(11.0f), 1e-4f);
  // A near plane at or behind the eye (orthographic), or none far away:
  // at most three decades.
  const glm::vec2 behind = tap_depth_map(glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, -5.0f, 10.0f));
  EXPECT_NEAR(1.0f / behind.y, std::log(1000.0f), 1e-3f);
  const glm::vec2 infinite = tap_depth_map(glm::infinitePerspective(0.6f, 1.0f, 0.1f));
  EXPECT_TRUE(std::isfinite(infinite.x) && std::isfinite(infinite.y) && infinite.y > 0.0f);
}

TEST(TapTexture, OneSurfaceWithinTheToleranceAnotherBeyondIt) {
  // 4% apart in depth is one surface (the shader's 5%); another surface is
  // one 5% and two storage steps apart (a step: 0.4% of the depth for
  // near and far planes 3x apart, 2.7% for the widest map, 1000x), after
  // 8-bit storage, over the whole range.
  for (const float far : {3.0f, 1000.0f}) {
    const glm::vec2 map = tap_depth_map(glm::perspective(0.6f, 1.0f, 1.0f, far));
    const float tolerance = tap_depth_tolerance(map);
    const float apart = std::exp(0.05f + 2.0f / (254.0f * map.y));
    EXPECT_LT(apart, far == 3.0f ? 1.07f : 1.12f);
    for (float d = 1.0f; d * apart < far; d *= 1.01f) {
      const float here = unorm8(encode_tap_depth(d, map));
      EXPECT_LE(std::abs(unorm8(encode_tap_depth(d * 1.04f, map)) - here), tolerance) << d;
      EXPECT_GT(std::abs(unorm8(encode_tap_depth(d * apart, map)) - here), tolerance) << d;
    }
  }
}

TEST(TapTexture, ValuesKeepTheirSharpenedRangeInSteps) {
  for (const float sharpen : {1.0f, 4.0f, 8.0f}) {
    const float scale = tap_value_scale(sharpen);
    const float step = 1.0f / (255.0f * scale);
    const float reach = 0.5f + 0.25f * sharpen;  // kept unclamped at least this far from 0.5
    for (float v = 0.5f - reach; v <= 0.5f + reach; v += 0.01f)
      EXPECT_NEAR(decode_tap_value(unorm8(encode_tap_value(v, scale)), scale), v,
                  0.5f * step + 1e-5f)
          << sharpen << " " << v;
  }
  EXPECT_LT(1.0f / (255.0f * tap_value_scale(4.0f)), 1.0f / 60.0f);
}

TEST(TapTexture, DirectionsAreUnitOrNone) {
  const glm::vec2 d = 2.0f * encode_tap_direction({3.0f, -4.0f}) - 1.0f;
  EXPECT_NEAR(d.x, 0.6f, 1e-6f);
  EXPECT_NEAR(d.y, -0.8f, 1e-6f);
  EXPECT_EQ(encode_tap_direction({0.0f, 0.0f}), glm::vec2(0.5f));
  EXPECT_EQ(encode_tap_direction({1e-8f, 0.0f}), glm::vec2(0.5f));
}

}  // namespace
}  // namespace ibfvs
