#include "ibfvs/render/feedback_images.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/texture/display.h"
#include "ibfvs/render/pass_settings.h"

namespace ibfvs {

FeedbackImages::Layout FeedbackImages::layout_for(const RenderSettings& settings, bool colour) {
  const shaders::ShaderFeatures f = shaders::features_for(settings, colour, false, false);
  return {colour, shaders::texture_channels(f), shaders::tap_texture(f)};
}

void FeedbackImages::allocate(glm::ivec2 size, const Layout& layout) {
  size_ = size;
  layout_ = layout;
  const gl::Format format = layout.channels == 4 ? gl::Format::RGBA16F : gl::Format::RG16F;
  for (int i = 0; i < 2; ++i) {
    texture_[i] = gl::Texture2D(size.x, size.y, format, true);
    taps_[i] =
        layout.taps ? gl::Texture2D(size.x, size.y, gl::Format::RGBA8, true) : gl::Texture2D();
  }
}

void FeedbackImages::convert(const Layout& layout, float sharpen) {
  if (layout == layout_) return;
  if (layout_.colour && !layout.colour)
    throw GraphicsError("renderer: a colour texture does not turn grey (a restart does)");
  ImageF raw = read_raw(sharpen);  // value, depth, displacement, tap value
  if (!layout_.colour && layout.colour)
    for (std::size_t i = 0; i < raw.pixels.size(); i += kRawChannels) {
      float* r = &raw.pixels[i];
      r[3] = r[1];  // RGB, depth; no direction in colour
      r[1] = r[2] = r[0];
      r[4] = 0.0f, r[5] = -1.0f;
    }
  allocate(size_, layout);
  upload_raw(raw, sharpen);
}

ImageF FeedbackImages::read_raw(float sharpen) const {
  const int w = size_.x, h = size_.y;
  ImageF stored(w, h, 4);
  texture_[last_].read_float(stored.pixels, 4);
  ImageF taps;
  if (taps_[last_]) {
    taps = ImageF(w, h, 4);
    taps_[last_].read_float(taps.pixels, 4);
  }
  const float scale = tap_value_scale(sharpen);
  const int channels = layout_.channels;  // of two, GL reads (0, 1) after them
  ImageF raw(w, h, kRawChannels, 0.0f);
  for (std::size_t i = 0; i < static_cast<std::size_t>(w) * h; ++i) {
    const float* s = &stored.pixels[4 * i];
    float* r = &raw.pixels[kRawChannels * i];
    std::copy_n(s, channels, r);
    r[5] = -1.0f;
    if (layout_.colour) continue;
    if (taps.pixels.empty()) {
      r[4] = s[0];
      continue;
    }
    const float* t = &taps.pixels[4 * i];
    r[2] = 2.0f * t[2] - 1.0f, r[3] = 2.0f * t[3] - 1.0f;  // the unit direction
    r[4] = decode_tap_value(t[0], scale);
    r[5] = t[1];
  }
  return raw;
}

void FeedbackImages::upload_raw(const ImageF& raw, float sharpen) {
  if (raw.width != size_.x || raw.height != size_.y || raw.channels != kRawChannels)
    throw InputError("renderer: the texture must be a " + std::to_string(size_.x) + "x" +
                     std::to_string(size_.y) + " image of " + std::to_string(kRawChannels) +
                     " channels");
  const std::size_t n = static_cast<std::size_t>(raw.width) * raw.height;
  const int channels = layout_.channels;
  const float scale = tap_value_scale(sharpen);
  const glm::vec2 map = tap_depth_[last_];
  std::vector<float> stored(n * static_cast<std::size_t>(channels));
  std::vector<float> taps(taps_[last_] ? n * 4 : 0);
  for (std::size_t i = 0; i < n; ++i) {
    const float* r = &raw.pixels[kRawChannels * i];
    std::copy_n(r, channels, &stored[channels * i]);
    if (!taps.empty()) {
      // As read_raw gives them, the stored tap depth and direction come
      // back unchanged (a stored direction is unit within 8 bits); a
      // displacement in pixels becomes its direction.
      const bool surface = r[1] > -255.0f;
      const glm::vec2 m(r[2], r[3]);
      const float length = std::sqrt(glm::dot(m, m));
      const glm::vec2 d = !surface                           ? glm::vec2(0.5f)
                          : length > 0.95f && length < 1.05f ? 0.5f + 0.5f * m
                                                             : encode_tap_direction(m);
      float* t = &taps[4 * i];
      t[0] = surface ? encode_tap_value(r[4], scale) : 0.5f;
      t[1] = !surface ? 0.0f : r[5] >= 0.0f ? r[5] : encode_tap_depth(r[1], map);
      t[2] = d.x, t[3] = d.y;
    }
  }
  texture_[last_].upload_float(stored, channels);
  if (!taps.empty()) taps_[last_].upload_float(taps, 4);
}

void FeedbackImages::upload_colours(std::span<const float> rgba) {
  if (!layout_.colour || rgba.size() != static_cast<std::size_t>(size_.x) * size_.y * 4)
    throw GraphicsError("renderer: colours go into a colour texture of its size");
  texture_[last_].upload_float(rgba, 4);
}

}  // namespace ibfvs
