#include "ibfvs/core/texture/reference.h"

#include <algorithm>
#include <cmath>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/texture/display.h"

namespace ibfvs {

ReferenceIbfvs::ReferenceIbfvs(int width, int height, float background, const NoiseParams& noise)
    : background_(background), noise_(width, height, noise) {
  texture_ = ImageF(width, height, 1, background);
  shown_ = taps_ = texture_;
  moved_ = ImageF(width, height, 2, 0.0f);
  covered_.assign(static_cast<std::size_t>(width) * height, 0);
}

float ReferenceIbfvs::sample_cubic(float x, float y) const {
  const float u = x - 0.5f, v = y - 0.5f;
  const float fu = std::floor(u), fv = std::floor(v);
  const int i = static_cast<int>(fu), j = static_cast<int>(fv);
  const auto weights = [](float f, float w[4]) {
    w[0] = f * (-0.5f + f * (1.0f - 0.5f * f));
    w[1] = 1.0f + f * f * (-2.5f + 1.5f * f);
    w[2] = f * (0.5f + f * (2.0f - 1.5f * f));
    w[3] = f * f * (-0.5f + 0.5f * f);
  };
  float wx[4], wy[4];
  weights(u - fu, wx);
  weights(v - fv, wy);
  const int w = texture_.width, h = texture_.height;
  // As the shader: the 4 x 4 texels but the four corners, renormalised.
  float sum = 0.0f, total = 0.0f;
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      if ((a == 0 || a == 3) && (b == 0 || b == 3)) continue;
      const int ti = std::clamp(i - 1 + a, 0, w - 1), tj = std::clamp(j - 1 + b, 0, h - 1);
      if (!covered_[static_cast<std::size_t>(tj) * w + ti]) return sample(x, y);
      sum += wx[a] * wy[b] * texture_.at(ti, tj);
      total += wx[a] * wy[b];
    }
  return std::clamp(sum / total, 0.0f, 1.0f);
}

bool ReferenceIbfvs::on_previous_surface(float x, float y) const {
  const int w = texture_.width, h = texture_.height;
  return x >= 0.0f && x <= static_cast<float>(w) && y >= 0.0f && y <= static_cast<float>(h) &&
         footprint_covered(x, y);
}

bool ReferenceIbfvs::footprint_covered(float x, float y) const {
  const int w = texture_.width, h = texture_.height;
  const float u = x - 0.5f, v = y - 0.5f;
  const float fu = std::floor(u), fv = std::floor(v);
  const int i = static_cast<int>(fu), j = static_cast<int>(fv);
  const float a = u - fu, b = v - fv;
  for (int dj = 0; dj < 2; ++dj)
    for (int di = 0; di < 2; ++di) {
      const float weight = (di ? a : 1 - a) * (dj ? b : 1 - b);
      const int ti = std::clamp(i + di, 0, w - 1), tj = std::clamp(j + dj, 0, h - 1);
      if (weight > 0.0f && !covered_[static_cast<std::size_t>(tj) * w + ti]) return false;
    }
  return true;
}

float ReferenceIbfvs::sample(float x, float y) const {
  return sample_bilinear(texture_, x, y, 0);
}

float ReferenceIbfvs::high_pass(glm::vec2 p, float value, glm::vec2 across) const {
  const glm::vec2 a = p + across, b = p - across;
  if (!footprint_covered(a.x, a.y) || !footprint_covered(b.x, b.y)) return 0.0f;
  return value - 0.5f * (sample(a.x, a.y) + sample(b.x, b.y));
}

void ReferenceIbfvs::step(const BackwardMap& map, int frame, float alpha, InjectMode mode) {
  if (map.width != texture_.width || map.height != texture_.height)
    throw InputError("reference: backward map size differs from the image size");
  ImageF next = texture_;
  ImageF shown = texture_;
  ImageF tap_values = texture_;
  ImageF moved(texture_.width, texture_.height, 2, 0.0f);
  const int taps = filter_taps(filter_length_);
  const float spacing = filter_spacing(filter_length_);
  const bool display = taps > 0 || sharpen_ > 0.0f;
  // As the GPU's tap texture (display.h): with the filter and sharpening the
  // taps read 8-bit values and directions.
  const bool tap_texture = taps > 0 && sharpen_ > 0.0f;
  const float scale = tap_value_scale(sharpen_);
  const float compensation = compensation_scale(alpha);
  const auto blend = [&](float prev, float g) {
    return mode == InjectMode::Blend ? (1 - alpha) * prev + alpha * g
                                     : std::min(1.0f, (1 - alpha) * prev + g);
  };
  const auto normalised = [](glm::vec2 v) { return v / std::sqrt(v.x * v.x + v.y * v.y); };
  for (int y = 0; y < texture_.height; ++y)
    for (int x = 0; x < texture_.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * texture_.width + x;
      if (!map.covered[i]) {
        next.pixels[i] = shown.pixels[i] = tap_values.pixels[i] = background_;
        continue;
      }
      const float g =
          noise_.sample(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, frame);
      const glm::vec2 s = map.source[i];
      const bool same = on_previous_surface(s.x, s.y) && (map.occluded.empty() || !map.occluded[i]);
      float prev = !same    ? (mode == InjectMode::Blend ? g : 0.0f)
                   : cubic_ ? sample_cubic(s.x, s.y)
                            : sample(s.x, s.y);
      const glm::vec2 here(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const glm::vec2 d = here - s;
      const float length = std::sqrt(d.x * d.x + d.y * d.y);
      // The streaks' direction: the flow's own displacement where the map
      // gives it, else the pixel's.
      const glm::vec2 flow = map.flow.empty() ? d : map.flow[i];
      const float flow_length = std::sqrt(flow.x * flow.x + flow.y * flow.y);
      const glm::vec2 along = flow_length > 1e-6f ? flow / flow_length
                              : length > 1e-6f    ? d / length
                                                  : glm::vec2(0.0f);
      if (compensated_ && same && length > 1e-6f) {
        // The compensated warp (display.h), as the fragment shader.
        const glm::vec2 across = kSharpenReach * glm::vec2(-along.y, along.x);
        const glm::vec2 f = glm::fract(s - 0.5f);
        const float v =
            f.x * (1.0f - f.x) * along.y * along.y + f.y * (1.0f - f.y) * along.x * along.x;
        prev = std::clamp(
            prev + compensation / (kSharpenReach * kSharpenReach) * v * high_pass(s, prev, across),
            0.0f, 1.0f);
      }
      next.pixels[i] = blend(prev, g);
      const glm::vec2 stored = encode_tap_direction(along);
      const glm::vec2 direction = 2.0f * glm::vec2(unorm8(stored.x), unorm8(stored.y)) - 1.0f;
      moved.at(x, y, 0) = tap_texture ? direction.x : along.x;
      moved.at(x, y, 1) = tap_texture ? direction.y : along.y;
      shown.pixels[i] = tap_values.pixels[i] = next.pixels[i];
      if (!(length > 1e-6f)) continue;
      // Sharpening once per pixel, as the fragment shader: the high-pass of
      // the last frame's F_t at the source and of this frame's noise here,
      // mixed as the values are; the taps read the sharpened values.
      float high_previous = 0.0f;
      if (sharpen_ > 0.0f) {
        const glm::vec2 across = kSharpenReach * glm::vec2(-along.y, along.x);
        if (same) high_previous = high_pass(s, prev, across);
        const glm::vec2 a = here + across, b = here - across;
        const float high_noise =
            g - 0.5f * (noise_.sample(a.x, a.y, frame) + noise_.sample(b.x, b.y, frame));
        const float high = mode == InjectMode::Add ? (1 - alpha) * high_previous + high_noise
                           : same ? (1 - alpha) * high_previous + alpha * high_noise
                                  : high_noise;
        tap_values.pixels[i] = next.pixels[i] + sharpen_ * high;
        if (tap_texture)
          tap_values.pixels[i] =
              decode_tap_value(unorm8(encode_tap_value(tap_values.pixels[i], scale)), scale);
      }
      if (!display || !same) continue;
      // The display filter, as the fragment shader: along the streamline
      // through the source in the last frame's sharpened F_t and stored
      // displacements.
      float sum = prev + sharpen_ * high_previous, weights = 1.0f;
      for (const float side : {-1.0f, 1.0f}) {
        glm::vec2 p = s, heading = side * along, last = heading;
        for (int k = 1; k <= taps; ++k) {
          const glm::vec2 turned = heading + 0.5f * (heading - last);
          p += spacing *
               (turned.x * turned.x + turned.y * turned.y > 1e-12f ? normalised(turned) : heading);
          if (!footprint_covered(p.x, p.y)) break;
          const glm::vec2 f(sample_bilinear(moved_, p.x, p.y, 0),
                            sample_bilinear(moved_, p.x, p.y, 1));
          if (!(std::sqrt(f.x * f.x + f.y * f.y) > (tap_texture ? 0.25f : 1e-6f))) break;
          last = heading;
          heading = side * normalised(f);
          if (heading.x * last.x + heading.y * last.y < 0.0f) break;
          const float w = filter_weight(filter_length_, k);
          sum += w * sample_bilinear(taps_, p.x, p.y, 0);
          weights += w;
        }
      }
      shown.pixels[i] = sum / weights;
    }
  texture_ = std::move(next);
  shown_ = std::move(shown);
  taps_ = std::move(tap_values);
  moved_ = std::move(moved);
  covered_ = map.covered;
}

}  // namespace ibfvs
