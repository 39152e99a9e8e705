#pragma once
// What a pass is compiled with (its features), and what follows from them
// alone: the layout of F_t, a tap texture beside it, the deferred pass. No
// GL: the page writer and the renderer both read it.

namespace ibfvs::shaders {

/// Optional parts of the IBFVS pass. Each program is compiled with only the
/// parts it uses: llvmpipe executes both sides of a branch, so a feature
/// switched off by a uniform would still cost its full price per pixel.
struct ShaderFeatures {
  bool object_noise = false;   ///< G on a 3D lattice (else the image-space grid)
  bool surface_image = false;  ///< an equirectangular image as the surface colour
  bool color_scalar = false;   ///< colour by the per-vertex colour scalar
  bool beta_scalar = false;    ///< beta modulated by the per-vertex beta scalar
  bool image_step = false;     ///< image-space normalisation of the step
  bool inject_add = false;     ///< add noise (particles) instead of blending (eq. 10)
  bool mono_texture = false;   ///< F_t is grey, stored in one channel (and its depth)
  bool cubic = false;          ///< F_t(t(x)) by Catmull-Rom instead of bilinear interpolation
  bool compensate = false;     ///< bilinear F_t(t(x)), its blur across the flow taken back
  int filter_taps = 0;         ///< taps per side of the display filter along the flow, 0..16
  bool contrast = false;       ///< the display's contrast stage
  bool record_flow = false;    ///< write each pixel's displacement (measurements)
  bool sharpen = false;        ///< display taps sharpened across the flow
  /// The surface moves: positions and normals per time step, and the
  /// advection from where the last frame drew each vertex
  bool moving = false;
  /// A distinct number per combination (a bit per flag of kFlags, then
  /// the taps).
  [[nodiscard]] unsigned key() const;
};

/// A flag of ShaderFeatures and the GLSL define it compiles in: the one
/// list the defines and key() go through.
struct FeatureFlag {
  bool ShaderFeatures::*member;
  const char* define;
};
inline constexpr FeatureFlag kFlags[] = {
    {&ShaderFeatures::object_noise, "IBFVS_OBJECT_NOISE"},
    {&ShaderFeatures::surface_image, "IBFVS_SURFACE_IMAGE"},
    {&ShaderFeatures::color_scalar, "IBFVS_COLOR_SCALAR"},
    {&ShaderFeatures::beta_scalar, "IBFVS_BETA_SCALAR"},
    {&ShaderFeatures::image_step, "IBFVS_IMAGE_STEP"},
    {&ShaderFeatures::inject_add, "IBFVS_INJECT_ADD"},
    {&ShaderFeatures::mono_texture, "IBFVS_MONO_TEXTURE"},
    {&ShaderFeatures::cubic, "IBFVS_CUBIC"},
    {&ShaderFeatures::compensate, "IBFVS_COMPENSATE"},
    {&ShaderFeatures::contrast, "IBFVS_CONTRAST"},
    {&ShaderFeatures::record_flow, "IBFVS_RECORD_FLOW"},
    {&ShaderFeatures::sharpen, "IBFVS_SHARPEN"},
    {&ShaderFeatures::moving, "IBFVS_MOVING"},
};

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

}  // namespace ibfvs::shaders
