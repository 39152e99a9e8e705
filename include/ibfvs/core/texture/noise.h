#pragma once
// The fresh-ink image G of IBFV (paper equations 6-8): a grid of random phases
// phi_ij, spaced s pixels apart, whose values cycle with a time profile w and
// are interpolated bilinearly (the triangular pulse h). The GPU shader and the
// CPU reference both evaluate exactly this.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ibfvs/core/support/hash.h"
#include "ibfvs/core/support/names.h"

namespace ibfvs {

/// The time profile w(t), period 1.
enum class NoiseProfile {
  Square,    ///< 1 for the first half of the period, 0 for the second
  Sawtooth,  ///< frac(t)
  Sine,      ///< 0.5 + 0.5 sin(2 pi t)
  Spike,     ///< 1 during the first `spike_width` of the period, else 0 (particles)
  /// Not periodic: a new random value every period, eased from the last one
  /// by a raised cosine. The noise never repeats, so the only structure that
  /// lasts from frame to frame is the one the flow carries: the pattern moves
  /// with the flow instead of being held back by noise fixed in the image.
  Random,
};

template <>
struct EnumNames<NoiseProfile> {
  static constexpr EnumName<NoiseProfile> table[] = {
      {NoiseProfile::Square, "square", "on for half the period"},
      {NoiseProfile::Sawtooth, "sawtooth", "rising through the period"},
      {NoiseProfile::Sine, "sine", "smooth"},
      {NoiseProfile::Spike, "spike", "on for spike_width of the period: particles"},
      {NoiseProfile::Random, "random",
       "a new random value each period, eased (never repeats: the pattern moves with the flow)"},
  };
};

/// Parameters of G.
struct NoiseParams {
  float scale = 4.0f;                           ///< s: pixels per grid cell
  NoiseProfile profile = NoiseProfile::Square;  ///< w
  float rate = 0.02f;                           ///< v_g: profile periods per frame
  std::uint32_t seed = 1;                       ///< seeds the phases phi_ij
  float spike_width = 0.1f;                     ///< fraction of the period a spike is on
  bool operator==(const NoiseParams&) const = default;
};

/// w(t) for the periodic profiles (Random is not periodic: cell_noise_value).
float noise_profile_value(NoiseProfile profile, float t, float spike_width);

/// The value of noise cell (i, j, k) at profile time t = v_g k + phi: w(t)
/// for the periodic profiles; for Random, r(n) eased into r(n + 1) with
/// n = floor(t) and r a hash of the cell and n (the shaders compute the same).
float cell_noise_value(const NoiseParams& params, int i, int j, int k, float t);

/// The phase grid of one image size, and G evaluated from it.
class NoiseGrid {
 public:
  /// Covers pixels [0, width) x [0, height): grid points i*s for
  /// i = 0 .. floor(width/s) + 1. Throws InputError for a scale <= 0.
  NoiseGrid(int width, int height, const NoiseParams& params);

  [[nodiscard]] int columns() const { return columns_; }
  [[nodiscard]] int rows() const { return rows_; }
  /// phi_ij in [0, 1), row-major (j * columns + i): uploaded as a texture.
  [[nodiscard]] const std::vector<float>& phases() const { return phases_; }
  [[nodiscard]] const NoiseParams& params() const { return params_; }

  /// G_ij;k = w(v_g k + phi_ij) (equation 8).
  [[nodiscard]] float grid_value(int i, int j, int frame) const;
  /// G(x; k) at image point (x, y) in pixels (equations 6-7), grid point
  /// (i, j) on the centre of pixel (i s, j s): at s = 1 each pixel centre
  /// takes one grid value (white noise).
  [[nodiscard]] float sample(float x, float y, int frame) const;

 private:
  NoiseParams params_;
  int columns_ = 0;
  int rows_ = 0;
  std::vector<float> phases_;
};

/// The phase of lattice point (i, j, k) of the solid noise: an integer hash
/// (a PCG step) that the fragment shader computes identically.
float solid_phase(int i, int j, int k, std::uint32_t seed);

/// G in object space (section 3.6, beyond the paper): the same time profile
/// on a 3D lattice of spacing `cell` world units, interpolated trilinearly at
/// the surface point, so the density is constant on the surface (figure 3,
/// right) and the noise stays on the surface when the camera moves.
float solid_noise(const NoiseParams& params, float cell, float x, float y, float z, int frame);

}  // namespace ibfvs
