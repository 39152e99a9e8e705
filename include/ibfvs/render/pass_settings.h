#pragma once
// What a program of the IBFVS pass is compiled with (its features) and set
// to (the uniforms that follow from the settings), from one place: the
// OpenGL renderer applies them, and the web page (page/web_page.h) carries the
// same list to the browser's runtime, which sets them by name.

#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibfvs/core/scene/render_settings.h"
#include "ibfvs/render/shader_features.h"

namespace ibfvs::shaders {

/// Whether F_t must hold colour: a background that is not grey (grey noise
/// on a grey background stays grey; random-cell colours switch a renderer
/// to colour as well).
[[nodiscard]] bool colour_background(const RenderSettings& settings);

/// The world length of the probe step of image-space normalisation: 1/1000
/// of the mesh's bounding-box diagonal.
[[nodiscard]] float probe_length(float diagonal);

/// The features of the pass for these settings. `colour_texture`: F_t holds
/// RGB (a coloured background or random cells), else grey; `surface_image`:
/// an equirectangular image is the surface colour; `record_flow`: the
/// displacement is written for measurements.
[[nodiscard]] ShaderFeatures features_for(const RenderSettings& settings, bool colour_texture,
                                          bool surface_image, bool record_flow);

/// One uniform's value: 1-4 components of a float, int or uint uniform, or
/// (array) a float array.
struct UniformValue {
  enum class Type { Float, Int, Uint };
  std::string name;
  Type type = Type::Float;
  std::vector<double> values;  // double: a uint32 seed stays exact
  bool array = false;
};

/// The IBFVS pass's uniforms that follow from the settings (not those that
/// change each frame: matrices, dt, noise time, shifts). `phase_size`: the
/// noise grid's columns and rows; `image_centre`: the centre of a spherical
/// surface image.
[[nodiscard]] std::vector<UniformValue> settings_uniforms(const RenderSettings& settings,
                                                          const ShaderFeatures& features,
                                                          glm::ivec2 phase_size,
                                                          glm::vec3 image_centre);

}  // namespace ibfvs::shaders
