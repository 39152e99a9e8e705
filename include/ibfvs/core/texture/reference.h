#pragma once
// CPU reference of the IBFVS texture synthesis (paper equations 3-8 and 10-12)
// on one grey channel. The GPU pass is tested against it.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "ibfvs/core/image/image.h"
#include "ibfvs/core/support/names.h"
#include "ibfvs/core/texture/noise.h"

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
  /// Optional (empty: none): 1 where the source lies on another surface
  /// than the pixel's in the previous frame (across an occlusion edge).
  std::vector<std::uint8_t> occluded;
  /// Optional (empty: the source's displacement): the flow's own
  /// displacement per pixel, in pixels, without the surface's or the
  /// camera's motion since the last frame. The streaks lie along it: the
  /// warp's compensation, sharpening and the display filter follow it.
  std::vector<glm::vec2> flow;
};

/// Image-space texture synthesis on the CPU.
class ReferenceIbfvs {
 public:
  /// F_t starts as the background everywhere (algorithm step 1).
  ReferenceIbfvs(int width, int height, float background, const NoiseParams& noise);

  /// One frame: F_t(x) = (1 - gamma) F_t,prev(source(x)) + gamma G(x; frame) with
  /// gamma = alpha on covered pixels; uncovered pixels become the background.
  /// F_t,prev is sampled bilinearly with texel centres at +0.5 and clamped
  /// edges, as a GL_LINEAR texture does. Where the source is outside the
  /// image, has a texel off the previous frame's surface in its bilinear
  /// footprint, or is occluded, F_t,prev(source(x)) is replaced by G(x; frame)
  /// (by 0 when adding: no ink yet): no background and no other surface
  /// flows in (section 3.5's inflow).
  void step(const BackwardMap& map, int frame, float alpha, InjectMode mode = InjectMode::Blend);
  /// The display filter (RenderSettings::filter_length, core/texture/display.h) for
  /// the next steps: shown() is, as the GPU pass computes it, a Gaussian
  /// along the streamline through the source in the last frame's F_t, which
  /// follows the displacements stored with it (second-order steps), without
  /// this frame's fresh noise; 0 shows F_t as it is.
  void set_filter_length(float length) { filter_length_ = length; }
  /// Each display tap plus k times its excess over the mean of its two
  /// neighbours 1.5 pixels across the flow (RenderSettings::sharpen), taken
  /// once per pixel as the GPU pass does (the high-pass of the last F_t at
  /// the source mixed with that of the fresh noise); 0 off.
  void set_sharpen(float k) { sharpen_ = k; }
  /// F_t,prev(source) by Catmull-Rom (RenderSettings::resample cubic) where
  /// the 4 x 4 texels around it were all on the surface, else bilinearly.
  void set_cubic(bool cubic) { cubic_ = cubic; }
  /// The compensated warp (RenderSettings::resample compensated,
  /// core/texture/display.h), its scale from the step's alpha as the GPU's.
  void set_compensated(bool on) { compensated_ = on; }

  /// D(F_t) of the last step before the contrast stage (one channel).
  [[nodiscard]] const ImageF& shown() const { return shown_; }

  [[nodiscard]] const ImageF& texture() const { return texture_; }
  /// Bilinear sample of F_t at (x, y) in pixels.
  [[nodiscard]] float sample(float x, float y) const;
  /// Whether the previous frame's surface covers the whole bilinear footprint
  /// of (x, y), inside the image.
  [[nodiscard]] bool on_previous_surface(float x, float y) const;

 private:
  // Whether every texel with a weight in the bilinear footprint of (x, y)
  // (clamped at the edges) was on the previous frame's surface.
  [[nodiscard]] bool footprint_covered(float x, float y) const;

  ImageF texture_;
  ImageF shown_;
  float filter_length_ = 0.0f;
  float sharpen_ = 0.0f;
  bool cubic_ = false;
  bool compensated_ = false;
  ImageF moved_;  // each pixel's displacement in the last frame (2 channels)
  ImageF taps_;   // the values the display taps read: F_t sharpened
  // `value` (F_t at p) less the mean of F_t at p +- across; 0 where one of
  // them is off the last frame's surface.
  [[nodiscard]] float high_pass(glm::vec2 p, float value, glm::vec2 across) const;
  [[nodiscard]] float sample_cubic(float x, float y) const;
  std::vector<std::uint8_t> covered_;  // the previous frame's surface
  float background_;
  NoiseGrid noise_;
};

}  // namespace ibfvs
