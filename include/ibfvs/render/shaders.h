#pragma once
// GLSL sources of the IBFVS pass, the noise grid pass and the statistics pass.

#include <string>

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
  int filter_taps = 0;         ///< taps per side of the display filter along the flow, 0..16
  bool contrast = false;       ///< the display's contrast stage
  bool record_flow = false;    ///< write each pixel's displacement (measurements)
  bool sharpen = false;        ///< display taps sharpened across the flow
  /// A distinct number per combination.
  [[nodiscard]] unsigned key() const;
};

std::string ibfvs_vertex_source(const ShaderFeatures& features);
std::string ibfvs_fragment_source(const ShaderFeatures& features);
extern const char* const kGridVertex;
std::string grid_fragment_source();
/// The statistics pass of the contrast stage (grey F_t in two channels, or colour).
std::string stats_fragment_source(bool mono_texture);
/// Copies F and the surface's depth into a host's framebuffer (ParaView's),
/// the background left as the host drew it.
extern const char* const kHostFragment;

}  // namespace ibfvs::shaders
