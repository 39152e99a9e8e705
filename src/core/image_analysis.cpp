#include "ibfvs/core/image_analysis.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace ibfvs {

ImageF gaussian_blur(const ImageF& image, float sigma) {
  constexpr int r = 2;
  float k[2 * r + 1];
  float sum = 0.0f;
  for (int i = -r; i <= r; ++i) sum += k[i + r] = std::exp(-0.5f * i * i / (sigma * sigma));
  for (float& v : k) v /= sum;
  const auto pass = [&](const ImageF& src, int dx, int dy) {
    ImageF dst = src;
    for (int y = 0; y < src.height; ++y)
      for (int x = 0; x < src.width; ++x)
        for (int c = 0; c < src.channels; ++c) {
          float acc = 0.0f;
          for (int i = -r; i <= r; ++i) {
            const int xx = std::clamp(x + i * dx, 0, src.width - 1);
            const int yy = std::clamp(y + i * dy, 0, src.height - 1);
            acc += k[i + r] * src.at(xx, yy, c);
          }
          dst.at(x, y, c) = acc;
        }
    return dst;
  };
  return pass(pass(image, 1, 0), 0, 1);
}

double flow_alignment(const ImageF& image, const std::vector<std::uint8_t>& mask,
                      const std::function<glm::vec2(float, float)>& flow, int margin) {
  const int w = image.width, h = image.height;
  // Distance to the nearest unmasked pixel, as a square (Chebyshev) erosion.
  std::vector<std::uint8_t> inner = mask;
  for (int step = 0; step < margin + 1; ++step) {
    std::vector<std::uint8_t> next = inner;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (!inner[y * w + x]) continue;
        for (int dy = -1; dy <= 1 && next[y * w + x]; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= w || yy >= h || !inner[yy * w + xx]) {
              next[y * w + x] = 0;
              break;
            }
          }
      }
    inner.swap(next);
  }
  const ImageF blurred = gaussian_blur(image, 1.0f);
  double along = 0.0, total = 0.0;
  for (int y = 1; y < h - 1; ++y)
    for (int x = 1; x < w - 1; ++x) {
      if (!inner[y * w + x]) continue;
      const auto p = [&](int dx, int dy) { return blurred.at(x + dx, y + dy, 0); };
      const float gx = (p(1, -1) + 2 * p(1, 0) + p(1, 1)) - (p(-1, -1) + 2 * p(-1, 0) + p(-1, 1));
      const float gy = (p(-1, 1) + 2 * p(0, 1) + p(1, 1)) - (p(-1, -1) + 2 * p(0, -1) + p(1, -1));
      glm::vec2 f = flow(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const float len = glm::length(f);
      if (!(len > 0.0f)) continue;
      f /= len;
      const glm::vec2 n(-f.y, f.x);
      const double gn = gx * n.x + gy * n.y;
      along += gn * gn;
      total += static_cast<double>(gx) * gx + static_cast<double>(gy) * gy;
    }
  return total > 0.0 ? along / total : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace ibfvs
