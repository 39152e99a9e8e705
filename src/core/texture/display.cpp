#include "ibfvs/core/texture/display.h"

#include <algorithm>
#include <cmath>

#include "ibfvs/core/support/error.h"

namespace ibfvs {

int display_stats_size(int width, int height) {
  int size = 1;
  while (size < 32 && 2 * size <= std::min(width, height)) size *= 2;
  return size;
}

float sample_bilinear(const ImageF& image, float x, float y, int c) {
  const float u = x - 0.5f, v = y - 0.5f;
  const float fu = std::floor(u), fv = std::floor(v);
  const int i = static_cast<int>(fu), j = static_cast<int>(fv);
  const float a = u - fu, b = v - fv;
  const auto t = [&](int ii, int jj) {
    return image.at(std::clamp(ii, 0, image.width - 1), std::clamp(jj, 0, image.height - 1), c);
  };
  return (1 - a) * (1 - b) * t(i, j) + a * (1 - b) * t(i + 1, j) + (1 - a) * b * t(i, j + 1) +
         a * b * t(i + 1, j + 1);
}

int filter_taps(float length) {
  if (!(length > 0.0f)) return 0;
  return std::clamp(static_cast<int>(std::ceil(length / 3.0f)), 1, 16);
}

float filter_spacing(float length) {
  const int n = filter_taps(length);
  return n > 0 ? length / (static_cast<float>(n) + 0.5f) : 0.0f;
}

float filter_weight(float length, int k) {
  const float d = filter_spacing(length) * static_cast<float>(k);
  return std::exp(-2.0f * d * d / (length * length));
}

}  // namespace ibfvs
