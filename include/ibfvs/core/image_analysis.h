#pragma once
// Measurements on rendered images that tests and tools share.

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec2.hpp>

#include "ibfvs/core/image.h"

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

/// Gaussian blur with a 5-tap kernel of the given sigma, clamped at the borders.
ImageF gaussian_blur(const ImageF& image, float sigma);

}  // namespace ibfvs
