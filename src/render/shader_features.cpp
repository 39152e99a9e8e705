#include "ibfvs/render/shader_features.h"

namespace ibfvs::shaders {

unsigned ShaderFeatures::key() const {
  unsigned k = 0, bit = 1;
  for (const FeatureFlag& flag : kFlags) {
    if (this->*flag.member) k |= bit;
    bit <<= 1;
  }
  return k | static_cast<unsigned>(filter_taps) * bit;
}

int texture_channels(const ShaderFeatures& f) {
  return !f.mono_texture || (f.filter_taps > 0 && !tap_texture(f)) ? 4 : 2;
}

bool tap_texture(const ShaderFeatures& f) {
  return f.mono_texture && f.filter_taps > 0 && f.sharpen;
}

bool deferred_pass(const ShaderFeatures& f) {
  return tap_texture(f) && !f.object_noise && !f.surface_image;
}

}  // namespace ibfvs::shaders
