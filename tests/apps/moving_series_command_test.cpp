// A moving mesh's series through `ibfvs render`, as a CFD user plays a
// rotating machine: between saved steps a turning part turns (a sliding
// interface stays closed, its texture aligned as well as elsewhere), and
// a series ends at its last step unless it is asked to loop.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "command_runner.h"
#include "helpers.h"
#include "ibfvs/core/image/image.h"
#include "ibfvs/core/image/image_analysis.h"
#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/mesh/mesh_io.h"

namespace ibfvs {
namespace {

using MovingSeriesCommand = test::CommandTest;
using test::Result;

constexpr float kPi = 3.14159265358979f;

// An annulus r0..r1 in z = 0 (or the part of it from angle 0 to `span`
// radians, less than a turn), `rings` x `sectors` quadrilaterals split in
// two, its points turned by `turn` radians about z; vectors: circles about
// z, v = (-y, x, 0) (the true flow, on every part, wherever it is).
void add_annulus(TriMesh& m, float r0, float r1, int rings, int sectors, float turn,
                 float span = 2.0f * kPi) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  const bool whole = span >= 2.0f * kPi;
  const int columns = whole ? sectors : sectors + 1;
  for (int r = 0; r <= rings; ++r)
    for (int k = 0; k < columns; ++k) {
      const float radius = r0 + (r1 - r0) * static_cast<float>(r) / static_cast<float>(rings);
      const float a = turn + span * static_cast<float>(k) / static_cast<float>(sectors);
      m.positions.push_back({radius * std::cos(a), radius * std::sin(a), 0.0f});
      m.normals.push_back({0.0f, 0.0f, 1.0f});
      m.vectors.push_back({-radius * std::sin(a), radius * std::cos(a), 0.0f});
    }
  const auto at = [&](int r, int k) {
    return base + static_cast<std::uint32_t>(r * columns + (k % columns));
  };
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < sectors; ++k) {
      m.triangles.push_back({at(r, k), at(r, k + 1), at(r + 1, k + 1)});
      m.triangles.push_back({at(r, k), at(r + 1, k + 1), at(r + 1, k)});
    }
}

struct Picture {
  ImageU8 image;
  glm::vec2 centre{0.0f};
  float radius = 0.0f;  // of the disc, in pixels
};

// The pixels that are not the black background: where the disc is.
bool covered(const ImageU8& image, int x, int y) {
  const std::size_t i = 4 * (static_cast<std::size_t>(y) * image.width + x);
  return image.pixels[i] > 6 || image.pixels[i + 1] > 6 || image.pixels[i + 2] > 6;
}

Picture picture(const std::filesystem::path& png) {
  Picture p{read_png(png)};
  double sx = 0.0, sy = 0.0, n = 0.0;
  for (int y = 0; y < p.image.height; ++y)
    for (int x = 0; x < p.image.width; ++x)
      if (covered(p.image, x, y)) {
        sx += x;
        sy += y;
        n += 1.0;
      }
  p.centre = glm::vec2(static_cast<float>(sx / n), static_cast<float>(sy / n));
  for (int y = 0; y < p.image.height; ++y)
    for (int x = 0; x < p.image.width; ++x)
      if (covered(p.image, x, y))
        p.radius = std::max(p.radius, glm::length(glm::vec2(x, y) - p.centre));
  return p;
}

std::string frame_name(int k) {
  char name[32];
  std::snprintf(name, sizeof name, "f%04d.png", k);
  return name;
}

TEST_F(MovingSeriesCommand, ASlidingInterfaceStaysClosedAndItsTextureAligned) {
  // A disc of two parts that share no point, as an arbitrary mesh interface
  // joins a rotor and a stator: the inner one (radius 0.5) turns 18 degrees
  // a step, the ring around it (overlapping it by 0.006, less than the
  // chord's cut of 0.0062 at mid-step) stands still.
  for (int k = 0; k < 4; ++k) {
    TriMesh m;
    add_annulus(m, 0.02f, 0.5f, 12, 96, 18.0f * kPi / 180.0f * static_cast<float>(k));
    add_annulus(m, 0.494f, 1.0f, 12, 96, 0.0f);
    write_ply(m, dir_ / ("disc_" + std::to_string(k) + ".ply"));
  }
  const Result r =
      run("render 'disc_*.ply' --field file --frames-per-step 6 --frames 19 --size 256x256 "
          "--background 0,0,0 --ortho --out f%04d.png -q");
  ASSERT_EQ(r.status, 0) << r.err;
  const Picture first = picture(dir_ / frame_name(0));
  ASSERT_GT(first.radius, 80.0f);
  double band = 0.0, rest = 0.0;
  for (int k = 0; k < 19; ++k) {
    const Picture p = picture(dir_ / frame_name(k));
    std::size_t holes = 0;
    std::vector<std::uint8_t> near(p.image.pixels.size() / 4), far(near.size());
    for (int y = 0; y < p.image.height; ++y)
      for (int x = 0; x < p.image.width; ++x) {
        const float d = glm::length(glm::vec2(x, y) - first.centre) / first.radius;
        if (d > 0.05f && d < 0.97f && !covered(p.image, x, y))
          ++holes;  // (a hole of 0.02 at the axis)
        const std::size_t i = static_cast<std::size_t>(y) * p.image.width + x;
        near[i] = std::abs(d - 0.5f) < 0.06f;
        far[i] = d > 0.2f && d < 0.9f && !near[i];
      }
    EXPECT_EQ(holes, 0u) << "frame " << k << ": background inside the disc";
    if (k < 10) continue;  // the texture formed
    const ImageF grey = to_float_channel(p.image, 1);
    const auto circles = [&](float x, float y) {
      const glm::vec2 d = glm::vec2(x, y) - first.centre;
      return glm::vec2(-d.y, d.x);
    };
    band += flow_alignment(grey, near, circles, 2) / 9.0;
    rest += flow_alignment(grey, far, circles, 2) / 9.0;
  }
  std::printf("sliding interface: alignment A %.3f along the interface, %.3f elsewhere\n", band,
              rest);
  EXPECT_GT(band, rest - 0.03);
  EXPECT_GT(rest, 0.8);
}

TEST_F(MovingSeriesCommand, ASeriesEndsAtItsLastStepUnlessItLoops) {
  // A half annulus turning 40 degrees a step, 3 steps, 4 frames a step: from
  // frame 8 on every frame shows the last step (not a blend back towards
  // the first, a state that never existed); with --loop frame 12 shows the
  // first step again.
  for (int k = 0; k < 3; ++k) {
    TriMesh m;
    add_annulus(m, 0.2f, 1.0f, 4, 24, 40.0f * kPi / 180.0f * static_cast<float>(k), kPi);
    add_annulus(m, 1.2f, 1.3f, 1, 48, 0.0f);  // still: every step's bounds and camera alike
    write_ply(m, dir_ / ("part_" + std::to_string(k) + ".ply"));
  }
  const auto coverage = [&](const std::string& png) {
    const ImageU8 image = read_png(dir_ / png);
    std::vector<bool> on(image.pixels.size() / 4);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        on[static_cast<std::size_t>(y) * image.width + x] = covered(image, x, y);
    return on;
  };
  const auto differ = [](const std::vector<bool>& a, const std::vector<bool>& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
    return n;
  };
  const std::string common = "--field file --size 96x96 --background 0,0,0 --ortho -q ";
  for (int k = 0; k < 3; k += 2) {
    const Result r = run("render 'part_*.ply' " + common + "--time " + std::to_string(k) +
                         " --frames 1 --out s" + std::to_string(k) + ".png");
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const std::vector<bool> first = coverage("s0.png"), last = coverage("s2.png");
  ASSERT_GT(differ(first, last), 300u);
  Result r =
      run("render 'part_*.ply' " + common + "--frames-per-step 4 --frames 16 --out f%04d.png");
  ASSERT_EQ(r.status, 0) << r.err;
  for (int k = 8; k < 16; ++k)
    EXPECT_LT(differ(coverage(frame_name(k)), last), 20u) << "frame " << k;
  r = run("render 'part_*.ply' " + common +
          "--frames-per-step 4 --frames 13 --loop --out f%04d.png");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_LT(differ(coverage(frame_name(12)), first), 20u);
  EXPECT_GT(differ(coverage(frame_name(10)), last), 100u);  // on its way back to the first
}

TEST_F(MovingSeriesCommand, ItsOptionsRefuseBadValuesInOneLine) {
  TriMesh m;
  add_annulus(m, 0.2f, 1.0f, 2, 12, 0.0f);
  write_ply(m, dir_ / "one.ply");
  expect_error("render one.ply --field file --field-frame sideways --out x.png",
               "--field-frame: expected surface or absolute, got 'sideways'");
  expect_error("render one.ply --field file --loop maybe --out x.png", "maybe");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.png"));
}

}  // namespace
}  // namespace ibfvs
