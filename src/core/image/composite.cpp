#include "ibfvs/core/image/composite.h"

#include <cstring>
#include <string>

#include "ibfvs/core/support/error.h"

namespace ibfvs {

std::vector<std::uint64_t> composite_keys(const ImageF& depth, int rank) {
  if (rank < 0) throw InputError("composite: a negative rank");
  if (depth.channels != 1) throw InputError("composite: the depth image needs one channel");
  std::vector<std::uint64_t> keys(depth.pixels.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const float d = depth.pixels[i];
    if (!(d >= 0.0f && d <= 1.0f))
      throw InputError("composite: a window depth outside [0, 1]: " + std::to_string(d));
    // Non-negative floats order as their bit patterns do.
    std::uint32_t bits = 0;
    std::memcpy(&bits, &d, sizeof bits);
    keys[i] = (static_cast<std::uint64_t>(bits) << 32u) | static_cast<std::uint32_t>(rank);
  }
  return keys;
}

void keep_won_pixels(ImageF& texture, std::span<const std::uint64_t> min_keys, int rank) {
  const auto channels = static_cast<std::size_t>(texture.channels);
  if (min_keys.size() * channels != texture.pixels.size())
    throw InputError("composite: " + std::to_string(min_keys.size()) + " keys for " +
                     std::to_string(texture.pixels.size() / channels) + " pixels");
  const auto me = static_cast<std::uint32_t>(rank);
  for (std::size_t i = 0; i < min_keys.size(); ++i)
    if (static_cast<std::uint32_t>(min_keys[i] & 0xffffffffu) != me)
      std::fill_n(texture.pixels.begin() + static_cast<std::ptrdiff_t>(i * channels), channels,
                  0.0f);
}

void composite_nearest(std::span<ImageF* const> images, const ImageF& depth,
                       const CompositeGroup& group) {
  if (group.size <= 1) return;
  for (const ImageF* image : images)
    if (depth.width != image->width || depth.height != image->height)
      throw InputError("composite: the depth and texture images differ in size");
  std::vector<std::uint64_t> keys = composite_keys(depth, group.rank);
  group.min_all(keys);
  for (ImageF* image : images) {
    keep_won_pixels(*image, keys, group.rank);
    group.sum_all(image->pixels);
  }
}

}  // namespace ibfvs
