#include <gtest/gtest.h>

#include <cmath>

#include "helpers.h"
#include "ibfvs/core/image/colormap.h"
#include "ibfvs/core/image/image.h"
#include "ibfvs/core/image/image_analysis.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"

namespace ibfvs {
namespace {

// Outputs are whole or absent: written under a temporary name, renamed when
// complete; an output abandoned leaves neither.
TEST(Image, OutputsAreRenamedWhenCompleteAndRemovedWhenNot) {
  test::TempDir dir;
  {
    PendingFile pending(dir / "a.png");
    EXPECT_EQ(pending.temporary().parent_path(), dir.path());
    EXPECT_EQ(pending.temporary().extension(), ".png");
    test::write_file(pending.temporary(), "partial");
  }  // abandoned
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
  test::write_file(dir / "b.png", "old");
  {
    PendingFile pending(dir / "b.png");
    test::write_file(pending.temporary(), "new");
    EXPECT_EQ(test::read_file(dir / "b.png"), "old");  // untouched until commit
    pending.commit();
  }
  EXPECT_EQ(test::read_file(dir / "b.png"), "new");
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1u);
  write_png(ImageU8(4, 4, 4), dir / "c.png");
  EXPECT_EQ(read_png(dir / "c.png").width, 4);
  EXPECT_TRUE(same_file(dir / "c.png", dir.path() / "." / "c.png"));
  EXPECT_FALSE(same_file(dir / "c.png", dir / "b.png"));
}

TEST(Image, PngRoundTripKeepsRowsBottomUp) {
  test::TempDir dir;
  ImageU8 img;
  img.width = 3;
  img.height = 2;
  img.channels = 4;
  for (int i = 0; i < 24; ++i) img.pixels.push_back(static_cast<std::uint8_t>(i * 10));
  write_png(img, dir / "a.png");
  const ImageU8 back = read_png(dir / "a.png");
  ASSERT_EQ(back.width, 3);
  ASSERT_EQ(back.height, 2);
  EXPECT_EQ(back.pixels, img.pixels);
}

TEST(Image, SixteenBitPngKeepsPrecision) {
  test::TempDir dir;
  ImageF img;
  img.width = 2;
  img.height = 1;
  img.channels = 1;
  img.pixels = {0.5001f, 0.25f};
  write_png16(img, dir / "f.png");
  const std::string bytes = test::read_file(dir / "f.png");
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  EXPECT_EQ(static_cast<unsigned char>(bytes[24]), 16u);  // IHDR bit depth
}

TEST(Image, ErrorsNameThePath) {
  test::TempDir dir;
  EXPECT_THROW(read_png(test::write_file(dir / "x.png", "not a png")), InputError);
  ImageU8 img;
  img.width = img.height = 1;
  img.pixels = {1, 2, 3, 4};
  try {
    write_png(img, dir / "missing" / "x.png");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing/x.png"), std::string::npos);
  }
}

TEST(Image, Yuv420PlanesAreTopDownBt601LimitedRange) {
  // 4x2, rows bottom-up: left 2x2 block red; right block white on top of black.
  ImageU8 img(4, 2, 4);
  const auto set = [&](int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    std::uint8_t* p = &img.pixels[(static_cast<std::size_t>(y) * 4 + x) * 4];
    p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
  };
  for (int y = 0; y < 2; ++y) set(0, y, 255, 0, 0), set(1, y, 255, 0, 0);
  set(2, 1, 255, 255, 255), set(3, 1, 255, 255, 255);  // top row (GL row 1)
  set(2, 0, 0, 0, 0), set(3, 0, 0, 0, 0);
  std::vector<std::uint8_t> yuv;
  to_yuv420(img, yuv);
  // Y top row first; red is (82, 90, 240), white 235, black 16, grey chroma 128.
  const std::vector<std::uint8_t> expected = {82,  82,  235, 235, 82, 82, 16, 16,  // Y
                                              90,  128,                            // U
                                              240, 128};                           // V
  EXPECT_EQ(yuv, expected);
  EXPECT_THROW(to_yuv420(ImageU8(3, 2, 4), yuv), InputError);
  EXPECT_THROW(to_yuv420(ImageU8(4, 2, 3), yuv), InputError);
}

TEST(ImageAnalysis, AlignmentOfStripes) {
  // Stripes along x: all gradient across the flow (1, 0) -> A = 1; across it -> 0.
  ImageF img;
  img.width = img.height = 64;
  img.channels = 1;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) img.pixels.push_back(std::sin(0.7f * static_cast<float>(y)));
  std::vector<std::uint8_t> mask(64 * 64, 1);
  const auto along = [](float, float) { return glm::vec2(1, 0); };
  const auto across = [](float, float) { return glm::vec2(0, 1); };
  EXPECT_GT(flow_alignment(img, mask, along, 2), 0.999);
  EXPECT_LT(flow_alignment(img, mask, across, 2), 0.001);
  // No pixel far enough from the unmasked ones: NaN.
  std::vector<std::uint8_t> thin(64 * 64, 0);
  thin[32 * 64 + 32] = 1;
  EXPECT_TRUE(std::isnan(flow_alignment(img, thin, along, 2)));
}

// Streaks along x whose value changes every `rows` rows at random: W grows
// with their width and is unbounded across the streaks' own direction.
TEST(ImageAnalysis, StreakWidthFollowsTheWidthOfTheStreaks) {
  const auto streaks = [](int rows) {
    ImageF img(128, 128, 1);
    std::uint32_t state = 12345;
    for (int y = 0; y < 128; y += rows) {
      state = state * 1664525u + 1013904223u;
      const float v = static_cast<float>(state >> 8) / 16777216.0f;
      for (int r = y; r < std::min(y + rows, 128); ++r)
        for (int x = 0; x < 128; ++x) img.at(x, r) = v;
    }
    return img;
  };
  std::vector<std::uint8_t> mask(128 * 128, 1);
  const auto along = [](float, float) { return glm::vec2(1, 0); };
  const auto across = [](float, float) { return glm::vec2(0, -1); };
  const double thin = streak_width(streaks(1), mask, along, 4);
  const double wide = streak_width(streaks(4), mask, along, 4);
  RecordProperty("thin", std::to_string(thin));
  EXPECT_GT(thin, 0.5);
  EXPECT_LT(thin, 1.1);
  // Band-passed (the 9-pixel mean taken off) streaks 4 pixels wide.
  EXPECT_GT(wide, thin + 0.4);
  EXPECT_LT(wide, 2.5);
  EXPECT_GE(streak_width(streaks(1), mask, across, 4), 10.0);
  std::vector<std::uint8_t> none(128 * 128, 0);
  EXPECT_TRUE(std::isnan(streak_width(streaks(1), none, along, 4)));
}

// Z tells smooth lines from lines with a zipper: random streaks along x are
// constant along the flow (Z 0), every second pixel of them raised and the
// others lowered is a zipper, and white noise has as much grain along as
// across (Z 1).
TEST(ImageAnalysis, GrainAlongTellsSmoothLinesFromAZipper) {
  ImageF smooth(96, 96, 1), zipper(96, 96, 1), white(96, 96, 1);
  std::uint32_t state = 777;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / 16777216.0f;
  };
  for (int y = 0; y < 96; ++y) {
    const float v = next();
    for (int x = 0; x < 96; ++x) {
      smooth.at(x, y) = v;
      zipper.at(x, y) = v + (x % 2 == 0 ? 0.3f : -0.3f);
      white.at(x, y) = next();
    }
  }
  std::vector<std::uint8_t> mask(96 * 96, 1);
  const auto along = [](float, float) { return glm::vec2(1, 0); };
  EXPECT_LT(grain_along(smooth, mask, along, 4), 1e-6);
  EXPECT_GT(grain_along(zipper, mask, along, 4), 1.0);
  EXPECT_NEAR(grain_along(white, mask, along, 4), 1.0, 0.1);
  std::vector<std::uint8_t> none(96 * 96, 0);
  EXPECT_TRUE(std::isnan(grain_along(smooth, none, along, 4)));
}

}  // namespace
}  // namespace ibfvs

namespace ibfvs {
namespace {

// A host's colour mapping (VTK's lookup tables): linear or base-10 log over
// the range, clamped, NaN kept for the host's NaN colour.
TEST(TablePositions, MapTheRangeLinearlyOrLogarithmicallyAndKeepNaN) {
  const float nan = std::nanf("");
  const std::vector<float> t =
      table_positions({-1.0f, 0.0f, 5.0f, 10.0f, 20.0f, nan}, 0.0, 10.0, false);
  EXPECT_FLOAT_EQ(t[0], 0.0f);
  EXPECT_FLOAT_EQ(t[1], 0.0f);
  EXPECT_FLOAT_EQ(t[2], 0.5f);
  EXPECT_FLOAT_EQ(t[3], 1.0f);
  EXPECT_FLOAT_EQ(t[4], 1.0f);
  EXPECT_TRUE(std::isnan(t[5]));
  const std::vector<float> l =
      table_positions({1.0f, 10.0f, 100.0f, 0.0f, -3.0f}, 1.0, 100.0, true);
  EXPECT_FLOAT_EQ(l[0], 0.0f);
  EXPECT_FLOAT_EQ(l[1], 0.5f);
  EXPECT_FLOAT_EQ(l[2], 1.0f);
  EXPECT_FLOAT_EQ(l[3], 0.0f);  // at or below 0: the low end
  EXPECT_FLOAT_EQ(l[4], 0.0f);
  // A log scale over a range that reaches 0 maps linearly (as VTK does).
  EXPECT_FLOAT_EQ(table_positions({5.0f}, 0.0, 10.0, true)[0], 0.5f);
  // A range of zero width: everything at the low end.
  EXPECT_FLOAT_EQ(table_positions({3.0f}, 3.0, 3.0, false)[0], 0.0f);
}

}  // namespace
}  // namespace ibfvs
