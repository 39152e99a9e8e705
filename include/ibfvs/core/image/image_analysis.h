#pragma once
// Measurements on rendered images that tests and tools share.

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec2.hpp>

#include "ibfvs/core/image/image.h"

namespace ibfvs {

/// Texture alignment with a known image-space flow:
///   A = sum((g . n)^2) / sum(|g|^2)
/// over masked pixels at least `margin` pixels from any unmasked pixel, with g
/// the Sobel gradient of the image after a Gaussian blur (sigma 1 pixel) and n
/// the unit normal to the flow direction. Streaks along the flow have their
/// gradients across it, so A approaches 1; isotropic noise gives about 0.5.
/// `flow(x, y)` gives the flow direction at pixel centre (x, y); pixels where
/// it is zero are skipped. Returns NaN when no pixel qualifies.
double flow_alignment(const ImageF& image, const std::vector<std::uint8_t>& mask,
                      const std::function<glm::vec2(float, float)>& flow, int margin);

/// Width in pixels of the streaks across a known image-space flow (the
/// companion of flow_alignment: A alone rewards any blur along the flow). The
/// first channel is band-passed (a Gaussian of 0.7 pixels minus the mean over
/// 9 x 9 pixels) and correlated with itself shifted s pixels along each
/// pixel's unit normal to the flow; W is the s at which the correlation falls
/// below 0.5 (interpolated between steps of 0.05 pixels). Pixels as for
/// flow_alignment; a shifted point must lie on the mask. A plain shaded
/// surface gives about 1.7, streaks one pixel wide about 0.8. NaN when too few
/// pixels qualify.
double streak_width(const ImageF& image, const std::vector<std::uint8_t>& mask,
                    const std::function<glm::vec2(float, float)>& flow, int margin);

/// Grain along the flow, Z: the mean square of the second difference one
/// pixel along each pixel's unit flow direction (2 v(x) - v(x + f) - v(x - f),
/// bilinear) over that of the second difference one pixel across it, on the
/// first channel. Smooth lines give little (Surface LIC on the motorbike:
/// 0.09-0.11); a zipper, grain or speckle along the lines gives more (white
/// noise: 1). Pixels as for flow_alignment. NaN when too few pixels qualify.
double grain_along(const ImageF& image, const std::vector<std::uint8_t>& mask,
                   const std::function<glm::vec2(float, float)>& flow, int margin);

/// The Rec. 709 luminance of an RGB(A) image, one channel.
ImageF luminance(const ImageF& rgb);

/// Gaussian blur with a 5-tap kernel of the given sigma, clamped at the borders.
ImageF gaussian_blur(const ImageF& image, float sigma);

/// How far the pattern moved between two frames `lag` frames apart, against
/// how far the flow moved. Every masked pixel of `after` is traced back `lag`
/// frames through `flow` (displacement per frame in pixels, 2 channels, as
/// IbfvsRenderer::read_flow gives it) scaled by a factor r, and `before` is
/// sampled there; the Pearson correlation of the two over the pixels whose
/// whole trace stays on the mask is computed for r = 0, 0.05, ... 1.5.
struct PatternMotion {
  double ratio = 0.0;      ///< the r of the best correlation: 1 moves with the flow
  double best = 0.0;       ///< the correlation there
  double at_flow = 0.0;    ///< the correlation at r = 1
  double still = 0.0;      ///< the correlation at r = 0 (a pattern fixed in the image)
  std::size_t pixels = 0;  ///< pixels that took part (at r = 1)
};
PatternMotion pattern_motion(const ImageF& before, const ImageF& after, const ImageF& flow,
                             const std::vector<std::uint8_t>& mask, int lag);

/// Standard deviation of the channel mean over the masked pixels (values in
/// [0, 1]): the RMS contrast of the image there.
double rms_contrast(const ImageF& image, const std::vector<std::uint8_t>& mask);

/// Fraction of the masked pixels of an RGB(A) image whose red exceeds the mean
/// of green and blue by more than `threshold`: surface pixels tinted by a red
/// background that flowed in.
double red_tinted_fraction(const ImageF& image, const std::vector<std::uint8_t>& mask,
                           float threshold = 0.02f);

}  // namespace ibfvs
