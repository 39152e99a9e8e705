#pragma once
// CPU reference of the IBFVS texture synthesis (paper equations 3-8 and 10-12)
// on one grey channel. The GPU pass is tested against it.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "ibfvs/core/image.h"
#include "ibfvs/core/names.h"
#include "ibfvs/core/noise.h"

namespace ibfvs {

/// How fresh ink G enters F_t.
enum class InjectMode {
  Blend,  ///< F_t = (1 - alpha) F_t(p_{k-1}) + alpha G (equation 10)
  Add,    ///< F_t = min(1, (1 - alpha) F_t(p_{k-1}) + G): bright particles (section 4.2)
};

template <>
struct EnumNames<InjectMode> {
  static constexpr EnumName<InjectMode> table[] = {
      {InjectMode::Blend, "blend", "eq. 10"},
      {InjectMode::Add, "add", "added ink: bright particles with the spike profile (4.2)"},
  };
};

/// For every pixel: whether the surface covers it, and where (in pixels) its
/// path line was one frame earlier, p'_{k-1} = T(r - v dt).
struct BackwardMap {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> covered;  ///< 1 where the projected surface covers the pixel
  std::vector<glm::vec2> source;      ///< previous position of the pixel centre, in pixels
};

/// Image-space texture synthesis on the CPU.
class ReferenceIbfvs {
 public:
  /// F_t starts as the background everywhere (algorithm step 1).
  ReferenceIbfvs(int width, int height, float background, const NoiseParams& noise);

  /// One frame: F_t(x) = (1 - gamma) F_t,prev(source(x)) + gamma G(x; frame) with
  /// gamma = alpha on covered pixels; uncovered pixels become the background.
  /// F_t,prev is sampled bilinearly with texel centres at +0.5 and clamped
  /// edges, as a GL_LINEAR texture does.
  void step(const BackwardMap& map, int frame, float alpha, InjectMode mode = InjectMode::Blend);

  [[nodiscard]] const ImageF& texture() const { return texture_; }
  /// Bilinear sample of F_t at (x, y) in pixels.
  [[nodiscard]] float sample(float x, float y) const;

 private:
  ImageF texture_;
  float background_;
  NoiseGrid noise_;
};

}  // namespace ibfvs
