#include "ibfvs/core/scene/render_settings.h"

#include <cmath>
#include <string>

#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/limits.h"

namespace ibfvs {
namespace {

bool in_unit(float v) {
  return v >= 0.0f && v <= 1.0f;
}

// Within the scene key's range (scene.h, key_range): one table.
bool in_key_range(std::string_view key, float v) {
  const KeyRange r = *key_range(key);
  return v >= r.min && v <= r.max;
}

}  // namespace

void RenderSettings::validate() const {
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
    throw SettingError("size", "width and height must be between 1 and " +
                                   std::to_string(kMaxImageSide) + " pixels");
  try {
    check_memory(image_bytes(width, height),
                 std::to_string(width) + "x" + std::to_string(height) + " pixels");
  } catch (const InputError& e) {
    throw SettingError("size", e.what());
  }
  if (!in_key_range("alpha", alpha)) throw SettingError("alpha", "must be between 0 and 1");
  if (!in_key_range("beta", beta)) throw SettingError("beta", "must be between 0 and 1");
  if (!color_table.empty() && color_table.size() != 256)
    throw SettingError("color_map", "a host's colour table needs 256 colours, not " +
                                        std::to_string(color_table.size()));
  if (!(image_step >= 0.0f) || !std::isfinite(image_step))
    throw SettingError("step", "the image-space step must be a finite number of pixels >= 0");
  if (!in_key_range("sharpen", sharpen))
    throw SettingError("sharpen", "must be between 0 (off) and 4");
  if (!in_key_range("filter", filter_length))
    throw SettingError("filter", "the filter length must be between 0 and 32 pixels");
  if (!in_key_range("contrast", contrast))
    throw SettingError("contrast", "the RMS contrast must be between 0 (off) and 0.5");
  if (object_noise && (!(object_cell > 0.0f) || !std::isfinite(object_cell)))
    throw SettingError("noise_space", "object: the cell size must be positive");
  if (!(noise.scale >= 1.0f) || !std::isfinite(noise.scale))
    throw SettingError("scale", "the noise scale must be at least 1 pixel");
  if (!std::isfinite(noise.rate)) throw SettingError("vg", "must be a finite number");
  if (!(noise.spike_width > 0.0f && noise.spike_width <= 1.0f))
    throw SettingError("spike_width", "must be in (0, 1]");
  for (int c = 0; c < 3; ++c) {
    if (!in_unit(background[c])) throw SettingError("background", "components must be in [0, 1]");
    if (!in_unit(surface_color[c]))
      throw SettingError("surface_color", "components must be in [0, 1]");
  }
  const auto check_range = [](glm::vec2 r, const char* option) {
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || !(r.y > r.x))
      throw SettingError(option, "needs two finite numbers LO,HI with LO < HI");
  };
  check_range(color_range, "color_range");
  check_range(beta_range, "beta_range");
}

}  // namespace ibfvs
