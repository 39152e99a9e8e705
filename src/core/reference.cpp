#include "ibfvs/core/reference.h"

#include <algorithm>
#include <cmath>

#include "ibfvs/core/error.h"

namespace ibfvs {

ReferenceIbfvs::ReferenceIbfvs(int width, int height, float background, const NoiseParams& noise)
    : background_(background), noise_(width, height, noise) {
  texture_ = ImageF(width, height, 1, background);
}

float ReferenceIbfvs::sample(float x, float y) const {
  const float u = x - 0.5f, v = y - 0.5f;
  const float fu = std::floor(u), fv = std::floor(v);
  const int i = static_cast<int>(fu), j = static_cast<int>(fv);
  const float a = u - fu, b = v - fv;
  const auto t = [&](int ii, int jj) {
    return texture_.at(std::clamp(ii, 0, texture_.width - 1),
                       std::clamp(jj, 0, texture_.height - 1));
  };
  return (1 - a) * (1 - b) * t(i, j) + a * (1 - b) * t(i + 1, j) + (1 - a) * b * t(i, j + 1) +
         a * b * t(i + 1, j + 1);
}

void ReferenceIbfvs::step(const BackwardMap& map, int frame, float alpha, InjectMode mode) {
  if (map.width != texture_.width || map.height != texture_.height)
    throw InputError("reference: backward map size differs from the image size");
  ImageF next = texture_;
  for (int y = 0; y < texture_.height; ++y)
    for (int x = 0; x < texture_.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * texture_.width + x;
      if (!map.covered[i]) {
        next.pixels[i] = background_;
        continue;
      }
      const float prev = sample(map.source[i].x, map.source[i].y);
      const float g =
          noise_.sample(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, frame);
      next.pixels[i] = mode == InjectMode::Blend ? (1 - alpha) * prev + alpha * g
                                                 : std::min(1.0f, (1 - alpha) * prev + g);
    }
  texture_ = std::move(next);
}

}  // namespace ibfvs
