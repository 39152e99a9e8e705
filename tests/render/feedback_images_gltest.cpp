// The images a frame hands the next (FeedbackImages) and the frame's
// targets (FrameTargets) on a real GL context: the raw form written and
// read back in each layout, a grey texture turned colour, and the targets
// cleared to the background.

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gl_fixture.h"
#include "ibfvs/core/texture/display.h"
#include "ibfvs/render/feedback_images.h"
#include "ibfvs/render/frame_plan.h"
#include "ibfvs/render/frame_targets.h"

namespace ibfvs {
namespace {

class FeedbackImagesGLTest : public test::GlTest {};

constexpr int kC = FeedbackImages::kRawChannels;
constexpr glm::ivec2 kSize(24, 16);

// A raw texture of the layout's kind: every fourth pixel off the surface,
// the rest at eye depths of 2-8 with values in [0, 1] and unit directions
// (or, in colour, RGB).
ImageF raw_texture(bool colour, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  ImageF raw(kSize.x, kSize.y, kC, 0.0f);
  for (std::size_t i = 0; i < raw.pixels.size() / kC; ++i) {
    float* r = &raw.pixels[kC * i];
    const bool surface = i % 4 != 0;
    r[0] = unit(random);
    r[1] = surface ? -(2.0f + 6.0f * unit(random)) : frame::kNoDepth;
    r[5] = -1.0f;
    if (colour) {
      r[1] = unit(random), r[2] = unit(random);
      r[3] = surface ? -(2.0f + 6.0f * unit(random)) : frame::kNoDepth;
      continue;
    }
    const float a = 6.2831853f * unit(random);
    if (surface) r[2] = std::cos(a), r[3] = std::sin(a);
    r[4] = surface ? unit(random) : r[0];
  }
  return raw;
}

float depth_of(const float* r, bool colour) {
  return colour ? r[3] : r[1];
}

TEST_F(FeedbackImagesGLTest, RawFormComesBackInEachLayout) {
  // 16-bit float F_t: values within half a unit in the last place (1e-3
  // relative); the taps' 8 bits: the value within a step of its spread
  // scale, the direction within a degree or so.
  const float sharpen = 4.0f, scale = tap_value_scale(sharpen);
  const glm::vec2 map = tap_depth_map(glm::perspective(0.7f, 1.0f, 1.0f, 10.0f));
  const FeedbackImages::Layout layouts[] = {
      {true, 4, false}, {false, 2, false}, {false, 4, false}, {false, 2, true}};
  for (const FeedbackImages::Layout& layout : layouts) {
    SCOPED_TRACE(testing::Message() << "colour " << layout.colour << ", " << layout.channels
                                    << " channels, taps " << layout.taps);
    FeedbackImages images;
    images.allocate(kSize, layout);
    images.set_tap_depth(images.last(), map);
    const ImageF raw = raw_texture(layout.colour, 7);
    images.upload_raw(raw, sharpen);
    const ImageF back = images.read_raw(sharpen);
    ASSERT_EQ(back.channels, kC);
    for (std::size_t i = 0; i < raw.pixels.size() / kC; ++i) {
      const float* r = &raw.pixels[kC * i];
      const float* b = &back.pixels[kC * i];
      const bool surface = depth_of(r, layout.colour) > -255.0f;
      for (int c = 0; c < layout.channels; ++c)
        if (c < 2 || !layout.taps) {
          ASSERT_NEAR(b[c], r[c], 1e-3f * std::max(1.0f, std::abs(r[c]))) << i << " " << c;
        }
      if (layout.colour) {
        EXPECT_EQ(b[4], 0.0f);
        EXPECT_EQ(b[5], -1.0f);
        continue;
      }
      if (!layout.taps) {
        EXPECT_EQ(b[4], b[0]) << i;  // the taps read the value itself
        EXPECT_EQ(b[5], -1.0f) << i;
        if (layout.channels == 2) {
          EXPECT_EQ(glm::vec2(b[2], b[3]), glm::vec2(0.0f)) << i;
        }
        continue;
      }
      if (!surface) {
        EXPECT_EQ(b[5], 0.0f) << i;  // no depth
        continue;
      }
      EXPECT_NEAR(b[4], r[4], 1.01f / (255.0f * scale) + 1e-3f) << i;
      EXPECT_NEAR(b[5], unorm8(encode_tap_depth(r[1], map)), 1e-6f) << i;
      const glm::vec2 d(b[2], b[3]);
      EXPECT_NEAR(glm::length(d), 1.0f, 0.01f) << i;
      EXPECT_GT(glm::dot(glm::normalize(d), glm::vec2(r[2], r[3])), std::cos(glm::radians(1.0f)))
          << i;
    }
    // What read_raw gave comes back the same: the raw form is a fixed point.
    images.upload_raw(back, sharpen);
    const ImageF again = images.read_raw(sharpen);
    for (std::size_t i = 0; i < back.pixels.size(); ++i)
      ASSERT_NEAR(again.pixels[i], back.pixels[i], 1e-6f) << i;
  }
}

TEST_F(FeedbackImagesGLTest, GreyTurnsColourWithItsValuesAndDepths) {
  FeedbackImages images;
  images.allocate(kSize, {false, 2, false});
  const ImageF grey = raw_texture(false, 11);
  images.upload_raw(grey, 0.0f);
  images.convert({true, 4, false}, 0.0f);
  EXPECT_TRUE(images.layout().colour);
  const ImageF back = images.read_raw(0.0f);
  for (std::size_t i = 0; i < grey.pixels.size() / kC; ++i) {
    const float* g = &grey.pixels[kC * i];
    const float* b = &back.pixels[kC * i];
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(b[c], g[0], 1e-3f) << i;
    ASSERT_NEAR(b[3], g[1], 1e-3f * std::abs(g[1])) << i;
  }
  EXPECT_THROW(images.convert({false, 2, false}, 0.0f), std::exception);  // a restart does that
}

TEST_F(FeedbackImagesGLTest, TargetsClearToTheBackground) {
  // Before a frame: F_t and F in the background, F_t's depth none, the
  // taps without depth or direction, the window depth far.
  FeedbackImages images;
  images.allocate(kSize, {false, 2, true});
  FrameTargets targets(kSize);
  targets.attach(images);
  targets.record_flow(true, images);
  images.upload_raw(raw_texture(false, 3), 4.0f);
  const glm::vec3 background(0.2f, 0.4f, 0.6f);
  targets.clear(images.last(), images, background);
  const ImageF raw = images.read_raw(4.0f);
  for (std::size_t i = 0; i < raw.pixels.size() / kC; ++i) {
    const float* r = &raw.pixels[kC * i];
    ASSERT_NEAR(r[0], background.r, 1e-3f) << i;
    ASSERT_EQ(r[1], frame::kNoDepth) << i;
    ASSERT_EQ(r[5], 0.0f) << i;
  }
  ImageU8 output;
  targets.read_output(output);
  for (std::size_t i = 0; i < output.pixels.size(); i += 4)
    ASSERT_EQ(glm::ivec4(output.pixels[i], output.pixels[i + 1], output.pixels[i + 2],
                         output.pixels[i + 3]),
              glm::ivec4(51, 102, 153, 255))
        << i;
  for (float d : targets.read_depth().pixels) ASSERT_EQ(d, 1.0f);
  for (float f : targets.read_flow().pixels) ASSERT_EQ(f, 0.0f);
}

}  // namespace
}  // namespace ibfvs
