#include <cmath>

#include <gtest/gtest.h>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/texture/noise.h"

namespace ibfvs {
namespace {

TEST(Noise, HashIsDeterministicAndUniform) {
  EXPECT_EQ(hash_uniform(7, 12345), hash_uniform(7, 12345));
  EXPECT_NE(hash_uniform(7, 12345), hash_uniform(8, 12345));
  double sum = 0;
  int low = 0;
  constexpr int n = 100000;
  for (int i = 0; i < n; ++i) {
    const float u = hash_uniform(3, static_cast<std::uint64_t>(i));
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    sum += u;
    low += u < 0.1f;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.01);
  EXPECT_NEAR(static_cast<double>(low) / n, 0.1, 0.01);
}

TEST(Noise, Profiles) {
  EXPECT_EQ(noise_profile_value(NoiseProfile::Square, 0.2f, 0.1f), 1.0f);
  EXPECT_EQ(noise_profile_value(NoiseProfile::Square, 1.7f, 0.1f), 0.0f);
  EXPECT_NEAR(noise_profile_value(NoiseProfile::Sawtooth, 2.25f, 0.1f), 0.25f, 1e-6f);
  EXPECT_NEAR(noise_profile_value(NoiseProfile::Sine, 0.25f, 0.1f), 1.0f, 1e-6f);
  EXPECT_NEAR(noise_profile_value(NoiseProfile::Sine, -0.25f, 0.1f), 0.0f, 1e-6f);
  EXPECT_EQ(noise_profile_value(NoiseProfile::Spike, 3.05f, 0.1f), 1.0f);
  EXPECT_EQ(noise_profile_value(NoiseProfile::Spike, 3.15f, 0.1f), 0.0f);
  EXPECT_EQ(parse_enum<NoiseProfile>("spike"), NoiseProfile::Spike);
  EXPECT_EQ(enum_name(NoiseProfile::Sawtooth), "sawtooth");
  EXPECT_THROW(parse_enum<NoiseProfile>("triangle"), InputError);
}

TEST(Noise, GridIsBilinearBetweenGridPoints) {
  NoiseParams p;
  p.scale = 4.0f;
  p.profile = NoiseProfile::Sawtooth;
  const NoiseGrid g(64, 32, p);
  EXPECT_EQ(g.columns(), 64 / 4 + 2);
  EXPECT_EQ(g.rows(), 32 / 4 + 2);
  for (int k : {0, 5}) {
    // Grid point (i, j) on the centre of pixel (i s, j s).
    EXPECT_FLOAT_EQ(g.sample(8.5f, 12.5f, k), g.grid_value(2, 3, k));
    const float mid = 0.25f * (g.grid_value(2, 3, k) + g.grid_value(3, 3, k) +
                               g.grid_value(2, 4, k) + g.grid_value(3, 4, k));
    EXPECT_NEAR(g.sample(10.5f, 14.5f, k), mid, 1e-6f);
  }
}

TEST(Noise, PixelFineNoiseIsOneGridValuePerPixel) {
  // At s = 1 every pixel centre takes its own grid value: white noise, no
  // neighbour shares any (the lines it makes are as thin as they can be).
  NoiseParams p;
  p.scale = 1.0f;
  const NoiseGrid g(16, 16, p);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i)
      EXPECT_FLOAT_EQ(g.sample(static_cast<float>(i) + 0.5f, static_cast<float>(j) + 0.5f, 3),
                      g.grid_value(i, j, 3));
}

TEST(Noise, SeedAndRateControlTheValues) {
  NoiseParams p;
  const NoiseGrid a(32, 32, p), b(32, 32, p);
  EXPECT_EQ(a.phases(), b.phases());
  p.seed = 2;
  const NoiseGrid c(32, 32, p);
  EXPECT_NE(a.phases(), c.phases());
  // Equation 8: G_ij;k = w(v_g k + phi_ij), so with v_g = 0 time stands still.
  p.rate = 0.0f;
  const NoiseGrid still(32, 32, p);
  EXPECT_EQ(still.grid_value(3, 4, 0), still.grid_value(3, 4, 97));
  // The square profile is on half the time: half the grid values are 1.
  p.rate = 0.05f;
  const NoiseGrid big(1024, 1024, p);
  int on = 0;
  for (int j = 0; j < big.rows(); ++j)
    for (int i = 0; i < big.columns(); ++i) on += big.grid_value(i, j, 13) > 0.5f;
  EXPECT_NEAR(static_cast<double>(on) / (big.rows() * big.columns()), 0.5, 0.02);
}

TEST(Noise, SolidNoiseIsALatticeOfPhases) {
  NoiseParams p;
  p.profile = NoiseProfile::Sawtooth;
  p.rate = 0.0f;
  // At lattice points the noise is the profile of the point's phase.
  EXPECT_NEAR(solid_noise(p, 0.5f, 1.0f, -0.5f, 1.5f, 0), solid_phase(2, -1, 3, p.seed), 1e-5f);
  EXPECT_NE(solid_phase(2, -1, 3, 1), solid_phase(2, -1, 3, 2));
  double sum = 0;
  for (int i = 0; i < 20000; ++i) sum += solid_phase(i % 31, i / 31, i % 7, 5);
  EXPECT_NEAR(sum / 20000, 0.5, 0.01);
  // Continuous: halfway between two points, the mean of their values.
  const float a = solid_phase(0, 0, 0, p.seed), b = solid_phase(1, 0, 0, p.seed);
  EXPECT_NEAR(solid_noise(p, 1.0f, 0.5f, 0.0f, 0.0f, 0), 0.5f * (a + b), 1e-5f);
}

TEST(Noise, RejectsBadScale) {
  NoiseParams p;
  p.scale = 0.0f;
  EXPECT_THROW(NoiseGrid(8, 8, p), InputError);
  p.scale = NAN;
  EXPECT_THROW(NoiseGrid(8, 8, p), InputError);
}

}  // namespace
}  // namespace ibfvs
