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

int filter_taps(float length) {
  if (!(length > 0.0f)) return 0;
  return std::clamp(static_cast<int>(std::ceil(length / 3.0f)), 1, 16);
}

float filter_spacing(float length) {
  const int n = filter_taps(length);
  return n > 0 ? length / (static_cast<float>(n) + 0.5f) : 0.0f;
}

float compensation_scale(float alpha) {
  return 1.0f + std::clamp(10.0f * alpha, 0.0f, 1.0f);
}

float tap_value_scale(float sharpen) {
  // The stored range spans 0.5 +- (0.5 + 3 k / 8) (k the gain), in steps of
  // 1/64 at the default k = 4. On the torus at the defaults 98% of the
  // sharpened values lie within 0.5 +- 0.6 and 0.2% beyond that range.
  return 1.0f / (1.0f + 0.75f * std::max(sharpen, 0.0f));
}

float encode_tap_value(float value, float scale) {
  return std::clamp(0.5f + (value - 0.5f) * scale, 0.0f, 1.0f);
}

float decode_tap_value(float stored, float scale) {
  return 0.5f + (stored - 0.5f) / scale;
}

glm::vec2 tap_depth_map(const glm::mat4& p) {
  float near = 0.0f, far = 0.0f;
  if (p[3][3] == 0.0f) {  // perspective: P[2][2] = -(f + n) / (f - n), P[3][2] = -2 f n / (f - n)
    near = p[3][2] / (p[2][2] - 1.0f);
    far = p[3][2] / (p[2][2] + 1.0f);
  } else {  // orthographic: P[2][2] = -2 / (f - n), P[3][2] = -(f + n) / (f - n)
    near = (p[3][2] + 1.0f) / p[2][2];
    far = (p[3][2] - 1.0f) / p[2][2];
  }
  if (!std::isfinite(far) || !(far > 0.0f))
    far = std::isfinite(near) && near > 0.0f ? 1e3f * near : 1.0f;
  const float lo = std::log(std::max({near, far * 1e-3f, 1e-30f})), hi = std::log(far);
  return {lo, hi > lo ? 1.0f / (hi - lo) : 1.0f};
}

float encode_tap_depth(float depth, glm::vec2 map) {
  const float t = std::clamp((std::log(std::max(depth, 1e-30f)) - map.x) * map.y, 0.0f, 1.0f);
  return (1.0f + 254.0f * t) / 255.0f;
}

float tap_depth_tolerance(glm::vec2 map) {
  return (0.05f * 254.0f * map.y + 1.0f) / 255.0f;
}

glm::vec2 encode_tap_direction(glm::vec2 d) {
  const float length = std::sqrt(d.x * d.x + d.y * d.y);
  return length > 1e-6f ? 0.5f + 0.5f * d / length : glm::vec2(0.5f);
}

float unorm8(float value) {
  return std::round(std::clamp(value, 0.0f, 1.0f) * 255.0f) / 255.0f;
}

float filter_weight(float length, int k) {
  const float d = filter_spacing(length) * static_cast<float>(k);
  return std::exp(-2.0f * d * d / (length * length));
}

}  // namespace ibfvs
