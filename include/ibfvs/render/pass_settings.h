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
#include "ibfvs/render/shaders.h"

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

/// Channels of F_t: a colour F_t holds RGB and the eye depth; a grey one the
/// value and the depth, plus each pixel's displacement when the display
/// filter follows it without a tap texture (2 channels are cheaper to read
/// on llvmpipe).
[[nodiscard]] int texture_channels(const ShaderFeatures& features);

/// Whether the pass keeps a second image beside a grey F_t for the display
/// filter's taps, (sharpened value, depth, displacement) in RGBA16F: when
/// the filter and sharpening are both on, so that each pixel sharpens once
/// and each tap reads one texel (the fragment shader's IBFVS_TAP_TEXTURE).
[[nodiscard]] bool tap_texture(const ShaderFeatures& features);

/// Whether the desktop renderer splits the IBFVS pass in two (the default
/// look's features): the triangles leave only what the pass needs of the
/// surface per pixel (gbuffer_fragment_source), and a pass over the surface's
/// pixels does the rest once each (resolve_fragment_source). On llvmpipe a
/// fragment of a small triangle shades a whole block of pixels, and hidden
/// ones shade too: on the motorbike the single pass was most of a frame. Not
/// with the solid noise or a surface image (they read object positions and
/// their derivatives per fragment); the browser page keeps the single pass.
[[nodiscard]] bool deferred_pass(const ShaderFeatures& features);

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
