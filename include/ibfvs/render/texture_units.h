#pragma once
// The texture unit of every sampler of the passes, in one table: the GLSL
// binds each sampler with BINDING(UNIT_NAME) (the prelude defines the
// names: shaders.h), the renderer binds its textures to the same constants,
// and the page's runtime sets each sampler's unit from those defines in the
// sources it is given and binds by the sampler's name. A pass's samplers
// share no unit; passes reuse units.

namespace ibfvs::units {

// The IBFVS pass (and its deferred halves).
inline constexpr int kPrevious = 0;      ///< u_previous: F_t of the last frame
inline constexpr int kGrid = 1;          ///< u_grid: this frame's noise grid values
inline constexpr int kColorMap = 2;      ///< u_color_map: 256 x 1
inline constexpr int kSurfaceImage = 3;  ///< u_surface_image: equirectangular
inline constexpr int kStats = 4;         ///< u_stats: the contrast statistics, 1 x 1
inline constexpr int kTaps = 5;          ///< u_taps: the last frame's tap texture
inline constexpr int kGBuffer0 = 6;      ///< u_gbuffer0: the deferred pass's first image
inline constexpr int kGBuffer1 = 7;      ///< u_gbuffer1: and its second
// The display pass (with kStats and kTaps).
inline constexpr int kStart = 1;    ///< u_start: the filter's seed
inline constexpr int kBase = 2;     ///< u_base: F_s weighted
inline constexpr int kTapsNow = 3;  ///< u_taps_now: this frame's taps
// The grid pass.
inline constexpr int kPhases = 0;  ///< u_phases: phi_ij
// The statistics pass.
inline constexpr int kTexture = 0;  ///< u_texture: F_t
inline constexpr int kShown = 1;    ///< u_shown: F
// The host pass.
inline constexpr int kOutput = 0;  ///< u_output: F
inline constexpr int kDepth = 1;   ///< u_depth: the surface's depth

/// The table as the GLSL names it (UNIT_PREVIOUS ...).
struct NamedUnit {
  const char* name;
  int unit;
};
inline constexpr NamedUnit kAll[] = {
    {"PREVIOUS", kPrevious},  {"GRID", kGrid},
    {"COLOR_MAP", kColorMap}, {"SURFACE_IMAGE", kSurfaceImage},
    {"STATS", kStats},        {"TAPS", kTaps},
    {"GBUFFER0", kGBuffer0},  {"GBUFFER1", kGBuffer1},
    {"START", kStart},        {"BASE", kBase},
    {"TAPS_NOW", kTapsNow},   {"PHASES", kPhases},
    {"TEXTURE", kTexture},    {"SHOWN", kShown},
    {"OUTPUT", kOutput},      {"DEPTH", kDepth},
};

}  // namespace ibfvs::units
