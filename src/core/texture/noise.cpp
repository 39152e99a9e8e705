#include "ibfvs/core/texture/noise.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ibfvs/core/support/error.h"

namespace ibfvs {

float noise_profile_value(NoiseProfile profile, float t, float spike_width) {
  const float f = t - std::floor(t);
  switch (profile) {
    case NoiseProfile::Square:
      return f < 0.5f ? 1.0f : 0.0f;
    case NoiseProfile::Sawtooth:
      return f;
    case NoiseProfile::Sine:
      return 0.5f + 0.5f * std::sin(2.0f * std::numbers::pi_v<float> * f);
    case NoiseProfile::Spike:
      return f < spike_width ? 1.0f : 0.0f;
    case NoiseProfile::Random:
      break;
  }
  return 0.0f;
}

float cell_noise_value(const NoiseParams& params, int i, int j, int k, float t) {
  if (params.profile != NoiseProfile::Random)
    return noise_profile_value(params.profile, t, params.spike_width);
  const float n = std::floor(t), f = t - n;
  // Cycle n hashes with a seed of its own (unsigned arithmetic wraps as GLSL's does).
  const auto cycle_seed = [&](float c) {
    return params.seed + static_cast<std::uint32_t>(static_cast<std::int32_t>(c)) * 0x9E3779B9u;
  };
  const float a = solid_phase(i, j, k, cycle_seed(n)), b = solid_phase(i, j, k, cycle_seed(n + 1));
  const float ease = 0.5f - 0.5f * std::cos(std::numbers::pi_v<float> * f);
  return a + (b - a) * ease;
}

NoiseGrid::NoiseGrid(int width, int height, const NoiseParams& params) : params_(params) {
  if (!(params.scale > 0.0f) || !std::isfinite(params.scale))
    throw SettingError("scale", "the noise scale must be a positive number of pixels");
  if (width <= 0 || height <= 0) throw InputError("noise grid: image size must be positive");
  columns_ = static_cast<int>(std::floor(static_cast<float>(width) / params.scale)) + 2;
  rows_ = static_cast<int>(std::floor(static_cast<float>(height) / params.scale)) + 2;
  phases_.resize(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_));
  for (std::size_t k = 0; k < phases_.size(); ++k) phases_[k] = hash_uniform(params.seed, k);
}

float NoiseGrid::grid_value(int i, int j, int frame) const {
  i = std::clamp(i, 0, columns_ - 1);
  j = std::clamp(j, 0, rows_ - 1);
  const float phi = phases_[static_cast<std::size_t>(j) * static_cast<std::size_t>(columns_) +
                            static_cast<std::size_t>(i)];
  return cell_noise_value(params_, i, j, 0, params_.rate * static_cast<float>(frame) + phi);
}

float NoiseGrid::sample(float x, float y, int frame) const {
  // Grid point (i, j) on the centre of pixel (i s, j s), as the shader's noise().
  const float u = (x - 0.5f) / params_.scale, v = (y - 0.5f) / params_.scale;
  const float fu = std::floor(u), fv = std::floor(v);
  const int i = static_cast<int>(fu), j = static_cast<int>(fv);
  const float a = u - fu, b = v - fv;
  return (1 - a) * (1 - b) * grid_value(i, j, frame) + a * (1 - b) * grid_value(i + 1, j, frame) +
         (1 - a) * b * grid_value(i, j + 1, frame) + a * b * grid_value(i + 1, j + 1, frame);
}

float solid_phase(int i, int j, int k, std::uint32_t seed) {
  std::uint32_t h = static_cast<std::uint32_t>(i) * 73856093u ^
                    static_cast<std::uint32_t>(j) * 19349663u ^
                    static_cast<std::uint32_t>(k) * 83492791u ^ seed * 2654435761u;
  const std::uint32_t state = h * 747796405u + 2891336453u;
  h = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  h = (h >> 22u) ^ h;
  return static_cast<float>(h >> 8) / 16777216.0f;
}

float solid_noise(const NoiseParams& params, float cell, float x, float y, float z, int frame) {
  const float u[3] = {x / cell, y / cell, z / cell};
  int i[3];
  float a[3];
  for (int c = 0; c < 3; ++c) {
    const float f = std::floor(u[c]);
    i[c] = static_cast<int>(f);
    a[c] = u[c] - f;
  }
  float g = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
    const float w = (dx ? a[0] : 1 - a[0]) * (dy ? a[1] : 1 - a[1]) * (dz ? a[2] : 1 - a[2]);
    const float phi = solid_phase(i[0] + dx, i[1] + dy, i[2] + dz, params.seed);
    g += w * cell_noise_value(params, i[0] + dx, i[1] + dy, i[2] + dz,
                              params.rate * static_cast<float>(frame) + phi);
  }
  return g;
}

}  // namespace ibfvs
