// The IBFVS pass's fragment outputs and the sampling of F_t (after
// ibfvs_fragment_inputs.glsl).
// F_t of this frame, its last channel the eye depth (the background holds
// kNoDepth): the next frame tells by it whether t(x) lands on this surface.
layout(location = 0) out vec4 o_texture;
#ifndef IBFVS_TAP_TEXTURE
// F; its alpha holds D(F_t) before the contrast stage, for the statistics
// (read_output sets it to 1): a third attachment would cost more per pixel.
layout(location = 1) out vec4 o_color;
#define IBFVS_FLOW_LOCATION 2
#else
// With the tap texture the display filter and the contrast stage run in the
// display pass, once per pixel of the surface (display_fragment_inputs.glsl); this
// pass leaves it F_s weighted, ((1 - beta) F_s, beta), and a seed: the
// filter's first tap, t(x)'s depth (or kNoFilter where no line starts) and
// the displacement.
layout(location = 1) out vec4 o_color;
// A grey F_t with the display filter and sharpening keeps a second image
// for the filter's taps, 8 bits a channel: (the sharpened value, depth,
// direction). Each pixel sharpens once here, and each tap then reads one
// texel, where it read three (the tap and its two neighbours across the
// flow: a third of the frame on llvmpipe). F_t itself is then (value, depth).
layout(location = 2) out vec4 o_taps;
#ifndef IBFVS_RESOLVE
layout(location = 3) out vec4 o_seed;
#define IBFVS_FLOW_LOCATION 4
#else
// The deferred pass's second half runs once per pixel of the surface, as the
// display pass does: it does the display pass's work too, and o_color is F.
#define IBFVS_FLOW_LOCATION 3
#endif
#endif
#ifdef IBFVS_RECORD_FLOW
layout(location = IBFVS_FLOW_LOCATION) out vec2 o_flow;  // this frame's displacement in pixels (measurements)
#endif
#if defined(IBFVS_CONTRAST) && !defined(IBFVS_TAP_TEXTURE)
flat in vec2 v_contrast;  // (mean, gain) of the contrast stage
#endif
#if defined(IBFVS_CONTRAST) && defined(IBFVS_RESOLVE)
BINDING(UNIT_STATS) uniform sampler2D u_stats;  // 1 x 1: (sum l, sum l^2, count)
#endif
BINDING(UNIT_PREVIOUS) uniform sampler2D u_previous;  // F_t of the last frame
BINDING(UNIT_GRID) uniform sampler2D u_grid;      // w(v_g k + phi_ij), this frame's grid values

uniform float u_alpha;
#ifdef IBFVS_COMPENSATE
uniform float u_compensation;  // s / reach^2 (core/texture/display.h)
#endif
uniform vec2 u_texture_shift;  // pixels: F_t moved with the mouse for this frame (3.7)
uniform vec2 u_noise_shift;    // pixels: G moved with the mouse, accumulated
uniform float u_beta;
uniform float u_noise_time;  // v_g k
uniform float u_noise_scale; // s
uniform ivec2 u_phase_size;
uniform vec3 u_surface_color;
uniform int u_locked;        // section 3.7: map F_t, do not update it
#ifdef IBFVS_SURFACE_IMAGE
BINDING(UNIT_SURFACE_IMAGE) uniform sampler2D u_surface_image;  // equirectangular, lon -180..180
uniform vec3 u_image_centre; // centre of the spherical mapping
#endif
#ifdef IBFVS_COLOR_SCALAR
BINDING(UNIT_COLOR_MAP) uniform sampler2D u_color_map;  // 256 x 1
uniform vec2 u_color_range;  // scalar values at the ends of the map
#endif
#ifdef IBFVS_BETA_SCALAR
uniform vec2 u_beta_range;   // beta is 0 at the first value, u_beta at the second
#endif

#ifndef IBFVS_OBJECT_NOISE
// Equations 6-7: grid values s pixels apart, triangular pulses = bilinear
// interpolation, which the texture unit does: grid point (i, j) sits on the
// centre of pixel (i s, j s), (i s + 0.5, j s + 0.5), and is the centre of
// texel (i, j). On pixel centres, pixel-fine noise (s = 1) is white: each
// pixel its own grid value, no neighbour sharing any (at the pixels' corners
// every pixel averaged four, and neighbours correlated by 0.5, which made
// the lines wide). The grid pass wrote this frame's values; the texture
// repeats, so the pattern wraps when shifted (3.7).
float noise(vec2 x) {
  return textureLod(u_grid, ((x - 0.5) / u_noise_scale + 0.5) / vec2(u_phase_size), 0.0).r;
}
#else
// Section 3.6 beyond the paper: G on a 3D lattice at the surface point.
uniform float u_object_cell;  // lattice spacing in world units
float solid_noise(vec3 p) {
  vec3 u = p / u_object_cell;
  vec3 fl = floor(u);
  ivec3 i = ivec3(fl);
  vec3 a = u - fl;
  float g = 0.0;
  for (int c = 0; c < 8; ++c) {
    ivec3 d = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    vec3 w3 = mix(1.0 - a, a, vec3(d));
    g += w3.x * w3.y * w3.z * cell_value(i + d, u_noise_time + solid_phase(i + d, u_seed));
  }
  return g;
}
#endif

