#pragma once
// Everything that shapes the IBFVS picture apart from mesh, field and camera:
// a plain description (no GL), filled from a scene and handed to the renderer.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

#include "ibfvs/core/image/colormap.h"
#include "ibfvs/core/support/names.h"
#include "ibfvs/core/texture/noise.h"
#include "ibfvs/core/texture/reference.h"

namespace ibfvs {

/// Which transform projects the advected point r - v dt (equation 13).
enum class AdvectView {
  Current,   ///< T_k, as the paper: under camera motion the texture stays in image space
  Previous,  ///< T_{k-1}: the texture follows the surface; same as Current for a still view
};

template <>
struct EnumNames<AdvectView> {
  static constexpr EnumName<AdvectView> table[] = {
      {AdvectView::Previous, "previous", "T_{k-1}: the texture stays on the surface"},
      {AdvectView::Current, "current", "T_k, as the 2003 paper"},
  };
};

/// What a field on a moving surface (a moving mesh's steps) is relative
/// to: it decides whether the surface's motion carries the texture. The
/// data cannot tell; docs/cfd.md, "Moving meshes", says which to choose.
enum class FieldFrame {
  Surface,   ///< a wall quantity (wall shear stress): the texture rides on the surface,
             ///< the field moves it on top (an oil film on a turning blade)
  Absolute,  ///< a velocity that holds the surface's motion already (U on a cut through a
             ///< rotating zone): the texture is not carried, the field alone moves it
};

template <>
struct EnumNames<FieldFrame> {
  static constexpr EnumName<FieldFrame> table[] = {
      {FieldFrame::Surface, "surface",
       "relative to the surface (a wall quantity): the texture rides on a moving surface"},
      {FieldFrame::Absolute, "absolute",
       "holds the surface's motion (U on a moving cut): the texture is not carried"},
  };
};

/// Whether a moving surface's own motion carries the texture (the renderer's
/// advection and a host's frame pacing both ask): advecting in the last
/// frame's view with a field relative to the surface.
inline bool carries_surface(AdvectView view, FieldFrame frame) {
  return view == AdvectView::Previous && frame == FieldFrame::Surface;
}

/// How F_t is sampled at t(x) (equation 13) each frame.
enum class Resample {
  Linear,       ///< bilinear, as the paper's texture mapping
  Cubic,        ///< Catmull-Rom: less blur accumulates across the flow (finer grain)
  Compensated,  ///< bilinear, its blur across the flow taken back (core/texture/display.h)
};

template <>
struct EnumNames<Resample> {
  static constexpr EnumName<Resample> table[] = {
      {Resample::Compensated, "compensated",
       "bilinear, its blur across the flow taken back (2 more taps, shared with sharpening)"},
      {Resample::Cubic, "cubic", "Catmull-Rom: a finer grain, 6 texture taps"},
      {Resample::Linear, "linear", "bilinear, as the paper (1 tap)"},
  };
};

/// Everything that shapes the picture apart from mesh, field and camera.
struct RenderSettings {
  int width = 512;                                ///< image width in pixels
  int height = 512;                               ///< image height in pixels
  float alpha = 0.1f;                             ///< blend weight of fresh noise (eq. 5, 12)
  float beta = 0.5f;                              ///< texture strength against shading (eq. 11)
  NoiseParams noise;                              ///< G (eq. 6-8)
  InjectMode inject = InjectMode::Blend;          ///< blend (eq. 10) or add (particles)
  glm::vec3 background{0.5f};                     ///< B, grey by default (section 3.5)
  glm::vec3 surface_color{0.82f, 0.80f, 0.76f};   ///< diffuse colour of the shaded surface F_s
  AdvectView advect_view = AdvectView::Previous;  ///< see AdvectView
  FieldFrame field_frame = FieldFrame::Surface;   ///< see FieldFrame
  bool object_noise = false;               ///< G on a 3D lattice at the surface point (section 3.6)
  float object_cell = 0.05f;               ///< its spacing in world units
  ColorMap color_map = ColorMap::Viridis;  ///< map for the colour scalar
  /// Non-empty: exactly 256 colours from the low to the high end of
  /// color_range, used instead of color_map (a host's lookup table, such as
  /// ParaView's colour map).
  std::vector<glm::vec3> color_table;
  bool use_color = false;             ///< colour F_s by the colour scalar (set_scalars)
  glm::vec2 color_range{0.0f, 1.0f};  ///< scalar values at the two ends of the map
  bool use_beta = false;              ///< modulate beta by the beta scalar (paper 3.3, step 7)
  glm::vec2 beta_range{0.0f, 1.0f};   ///< beta scalar at which the texture strength is 0 and beta
  /// > 0: normalise the flow in image space, every vector moving this many
  /// pixels per frame (paper figure 2; image_normalized_step); dt then only
  /// says whether to move (0 stops, as when locked).
  float image_step = 0.0f;
  /// Display only (the feedback loop keeps F_t as synthesised): length L in
  /// pixels of a Gaussian filter along the curved streamline through the
  /// pixel's source in the last frame's F_t (core/texture/display.h: ceil(L / 2)
  /// taps each side); 0 shows F_t as it is.
  float filter_length = 0.0f;
  Resample resample = Resample::Linear;  ///< how F_t is sampled at t(x)
  /// Display only: each tap of the display filter plus k times its excess
  /// over the mean of its two neighbours 1.5 pixels across the flow, which
  /// counters the blur that each frame's resampling leaves across it
  /// (thinner lines); 0 off.
  float sharpen = 0.0f;
  /// Display only: the displayed texture's values moved to mean 0.5 and this
  /// standard deviation (RMS contrast) over the surface; 0 leaves them.
  float contrast = 0.0f;

  /// Throws SettingError naming the first impossible value by its scene key.
  void validate() const;
  bool operator==(const RenderSettings&) const = default;
};

}  // namespace ibfvs
