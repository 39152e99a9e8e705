#include "ibfvs/render/pass_settings.h"

#include "ibfvs/core/texture/display.h"

namespace ibfvs::shaders {

bool colour_background(const RenderSettings& settings) {
  const glm::vec3& c = settings.background;
  return !(c.r == c.g && c.g == c.b);
}

float probe_length(float diagonal) {
  return diagonal > 0.0f ? 1e-3f * diagonal : 1e-3f;
}

ShaderFeatures features_for(const RenderSettings& settings, bool colour_texture, bool surface_image,
                            bool record_flow) {
  ShaderFeatures f;
  f.object_noise = settings.object_noise;
  f.surface_image = surface_image;
  f.color_scalar = settings.use_color;
  f.beta_scalar = settings.use_beta;
  f.image_step = settings.image_step > 0.0f;
  f.inject_add = settings.inject == InjectMode::Add;
  f.mono_texture = !colour_texture;
  f.cubic = settings.resample == Resample::Cubic;
  f.compensate = settings.resample == Resample::Compensated;
  f.filter_taps = ibfvs::filter_taps(settings.filter_length);
  f.contrast = settings.contrast > 0.0f;
  f.record_flow = record_flow;
  f.sharpen = settings.sharpen > 0.0f;
  return f;
}

std::vector<UniformValue> settings_uniforms(const RenderSettings& s, const ShaderFeatures& f,
                                            glm::ivec2 phase_size, glm::vec3 image_centre) {
  using T = UniformValue::Type;
  const auto w = static_cast<float>(s.width), h = static_cast<float>(s.height);
  std::vector<UniformValue> u = {
      {"u_alpha", T::Float, {s.alpha}},
      {"u_beta", T::Float, {s.beta}},
      {"u_profile", T::Int, {static_cast<float>(static_cast<int>(s.noise.profile))}},
      {"u_spike_width", T::Float, {s.noise.spike_width}},
      {"u_surface_color", T::Float, {s.surface_color.r, s.surface_color.g, s.surface_color.b}},
      {"u_object_cell", T::Float, {s.object_cell}},
      {"u_seed", T::Uint, {static_cast<double>(s.noise.seed)}},
      {"u_image_step", T::Float, {s.image_step}},
      {"u_size", T::Float, {w, h}},
      {"u_color_range", T::Float, {s.color_range.x, s.color_range.y}},
      {"u_beta_range", T::Float, {s.beta_range.x, s.beta_range.y}},
      {"u_noise_scale", T::Float, {s.noise.scale}},
      {"u_phase_size",
       T::Int,
       {static_cast<float>(phase_size.x), static_cast<float>(phase_size.y)}},
      {"u_inverse_size", T::Float, {1.0f / w, 1.0f / h}},
      {"u_image_centre", T::Float, {image_centre.x, image_centre.y, image_centre.z}},
      {"u_contrast", T::Float, {s.contrast}},
      {"u_sharpen", T::Float, {s.sharpen}},
  };
  if (f.compensate)  // c = s v / reach^2 (display.h): the shader multiplies by v
    u.push_back({"u_compensation",
                 T::Float,
                 {compensation_scale(s.alpha) / (kSharpenReach * kSharpenReach)}});
  if (tap_texture(f)) u.push_back({"u_tap_value_scale", T::Float, {tap_value_scale(s.sharpen)}});
  if (f.filter_taps > 0) {
    UniformValue weights{"u_filter_weights", T::Float, {}, true};
    for (int k = 0; k < f.filter_taps; ++k)
      weights.values.push_back(filter_weight(s.filter_length, k + 1));
    u.push_back({"u_filter_spacing", T::Float, {filter_spacing(s.filter_length)}});
    u.push_back(std::move(weights));
  }
  return u;
}

}  // namespace ibfvs::shaders
