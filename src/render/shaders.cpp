// The passes' GLSL, one generator for desktop GL and WebGL2. Sections: the
// IBFVS pass's vertex shader (kIbfvsVertexBody); the grid and display
// passes' full-screen triangle; the noise profile; the IBFVS pass's fragment
// head (its inputs: the varyings, or the deferred pass's two images; and the
// deferred pass's first half); the IBFVS pass's fragment main (also the
// deferred pass's second half); the grid and statistics passes; the
// dialects and the sources put together. The display filter, the contrast
// stage and the display pass are in display_shaders.cpp.
#include "ibfvs/render/shaders.h"

#include <string>

#include "ibfvs/core/texture/display.h"
#include "ibfvs/render/pass_settings.h"
#include "shader_parts.h"

namespace ibfvs::shaders {

using parts::kContrast;
using parts::kDisplayFilter;
using parts::kDisplayFragmentHead;
using parts::kDisplayFragmentMain;

namespace {

const char* const kIbfvsVertexBody = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_vector;       // the field at the current time step
layout(location = 4) in vec3 a_vector_next;  // and at the next one (unsteady flow)
layout(location = 3) in vec2 a_scalars;  // (colour scalar, beta scalar)
#ifdef IBFVS_MOVING
// A moving or deforming surface: its positions and normals at the current
// (a_position, a_normal) and the next time step, mixed like the field, and
// where the last frame drew each vertex (between a_drawn and a_drawn_next
// at u_drawn_mix: the pair of steps that frame drew).
layout(location = 5) in vec3 a_position_next;
layout(location = 6) in vec3 a_normal_next;
layout(location = 7) in vec3 a_drawn;
layout(location = 8) in vec3 a_drawn_next;
uniform float u_drawn_mix;
#endif

uniform mat4 u_view_projection;          // T_k: where the vertex is drawn
uniform mat4 u_advect_view_projection;   // T_k or T_{k-1}: where its texture comes from
uniform mat4 u_view;
uniform float u_dt;
uniform float u_field_mix;  // 0: a_vector, 1: a_vector_next
#ifdef IBFVS_IMAGE_STEP
uniform float u_image_step;  // every vector moves this many pixels (image-space normalisation)
uniform float u_probe;       // world length of the probe step for it
uniform vec2 u_size;         // image size in pixels
#endif

// Equation 13, t = T(r - v dt), evaluated per fragment: the homogeneous
// clip-space point T(r_i - v_i dt) of each vertex is interpolated
// perspective-correctly, which gives exactly T(r(x) - v(x) dt) for the
// surface point r(x) under the pixel, and the fragment divides by w. On small
// triangles this equals the paper's screen-linear interpolation of t_i; on
// large triangles in perspective it is exact where both vertex-level
// interpolations err (section 3.9's artifact). It also avoids noperspective
// varyings, which llvmpipe (Mesa 22.3) corrupts on triangles it clips.
out vec4 v_from;
// The flow's own displacement in the last frame's image (normalised device
// units): where the last frame drew the point less t(x), without the
// surface's or the camera's motion since. The streaks lie along it; a
// surface that jumped (a time step of a moving mesh) or a turning camera
// adds its motion to x - t(x), which the display must not follow.
#ifdef IBFVS_STREAKS
out vec2 v_flow;
#endif
#if defined(IBFVS_COLOR_SCALAR) || defined(IBFVS_BETA_SCALAR)
out vec2 v_scalars;
#endif
out vec3 v_normal_eye;
out vec3 v_position_eye;
#if defined(IBFVS_SURFACE_IMAGE) || defined(IBFVS_OBJECT_NOISE)
out vec3 v_position_object;  // for the spherical image map and the solid noise
#endif
#if defined(IBFVS_CONTRAST) && !defined(IBFVS_TAP_TEXTURE)
// The contrast stage's mean and gain from the last frame's statistics, read
// per vertex (the same for all) rather than per pixel.
BINDING(4) uniform sampler2D u_stats;  // 1 x 1: (sum l, sum l^2, count)
flat out vec2 v_contrast;
#endif
void main() {
#if defined(IBFVS_CONTRAST) && !defined(IBFVS_TAP_TEXTURE)
  v_contrast = contrast_stage(texelFetch(u_stats, ivec2(0), 0).xyz);
#endif
#ifdef IBFVS_MOVING
  vec3 position = mix(a_position, a_position_next, u_field_mix);
  vec3 normal = mix(a_normal, a_normal_next, u_field_mix);
  // The surface's own motion enters the advection as the camera's does:
  // the texture comes from where the last frame drew this point.
  vec3 drawn = mix(a_drawn, a_drawn_next, u_drawn_mix);
#else
  vec3 position = a_position;
  vec3 normal = a_normal;
  vec3 drawn = a_position;
#endif
  gl_Position = u_view_projection * vec4(position, 1.0);
  vec3 v = mix(a_vector, a_vector_next, u_field_mix);
  vec3 step = v * u_dt;
#ifdef IBFVS_IMAGE_STEP
  {  // as image_normalized_step() in core/scene/camera.cpp
    step = vec3(0.0);
    float speed = length(v);
    vec4 a = u_advect_view_projection * vec4(drawn, 1.0);
    vec4 b = u_advect_view_projection * vec4(drawn - v / max(speed, 1e-30) * u_probe, 1.0);
    if (speed > 0.0 && u_dt > 0.0 && a.w > 1e-6 && b.w > 1e-6) {
      float moved = length((a.xy / a.w - b.xy / b.w) * 0.5 * u_size);
      if (moved > 0.0) step = v / speed * (u_probe * min(u_image_step / moved, 50.0));
    }
  }
#endif
  v_from = u_advect_view_projection * vec4(drawn - step, 1.0);
#ifdef IBFVS_STREAKS
  vec4 still = u_advect_view_projection * vec4(drawn, 1.0);
  v_flow = still.w > 1e-6 && v_from.w > 1e-6 ? still.xy / still.w - v_from.xy / v_from.w : vec2(0.0);
#endif
#if defined(IBFVS_COLOR_SCALAR) || defined(IBFVS_BETA_SCALAR)
  v_scalars = a_scalars;
#endif
  v_normal_eye = mat3(u_view) * normal;
  v_position_eye = (u_view * vec4(position, 1.0)).xyz;
#if defined(IBFVS_SURFACE_IMAGE) || defined(IBFVS_OBJECT_NOISE)
  v_position_object = position;
#endif
}
)";

// The grid pass's vertex shader: one triangle that covers the viewport; the
// display pass's lies on the far plane, so that a depth test of GREATER
// passes where the IBFVS pass drew the surface and nowhere else.
const char* const kGridVertexBody = R"(
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
#ifdef IBFVS_FAR
  gl_Position = vec4(p * 2.0 - 1.0, 1.0, 1.0);
#else
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
#endif
}
)";

// The noise time profile w(t), period 1 (equation 8): shared by the grid pass
// and the object-space noise of the IBFVS pass.
const char* const kProfile = R"(
uniform int u_profile;  // 0 square, 1 sawtooth, 2 sine, 3 spike, 4 random
uniform float u_spike_width;
uniform uint u_seed;
// solid_phase() of noise.cpp, bit for bit: a PCG step of the lattice point.
float solid_phase(ivec3 i, uint seed) {
  uint h = uint(i.x) * 73856093u ^ uint(i.y) * 19349663u ^ uint(i.z) * 83492791u ^
           seed * 2654435761u;
  uint state = h * 747796405u + 2891336453u;
  h = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  h = (h >> 22u) ^ h;
  return float(h >> 8) / 16777216.0;
}
// cell_noise_value() of noise.cpp: w(t), or for the random profile a new
// value per period eased from the last one.
float cell_value(ivec3 cell, float t) {
  float n = floor(t), f = t - n;
  if (u_profile == 4) {
    uint c = uint(int(n));
    float a = solid_phase(cell, u_seed + c * 0x9E3779B9u);
    float b = solid_phase(cell, u_seed + (c + 1u) * 0x9E3779B9u);
    return a + (b - a) * (0.5 - 0.5 * cos(3.14159265359 * f));
  }
  if (u_profile == 0) return f < 0.5 ? 1.0 : 0.0;
  if (u_profile == 1) return f;
  if (u_profile == 2) return 0.5 + 0.5 * sin(6.28318530718 * f);
  return f < u_spike_width ? 1.0 : 0.0;
}
)";

// Features a renderer does not use are compiled out (ShaderFeatures), not
// skipped by uniform branches: llvmpipe runs both sides of every branch.
const char* const kIbfvsFragmentHead = R"(
uniform vec2 u_inverse_size;  // 1 / image size in pixels
#ifndef IBFVS_RESOLVE
in vec4 v_from;
#ifdef IBFVS_STREAKS
in vec2 v_flow;
#endif
uniform vec2 u_clip_to_depth;  // (a, b): eye depth = a clip.z + b clip.w (this projection)
#if defined(IBFVS_COLOR_SCALAR) || defined(IBFVS_BETA_SCALAR)
in vec2 v_scalars;
#endif
in vec3 v_normal_eye;
in vec3 v_position_eye;
#if defined(IBFVS_SURFACE_IMAGE) || defined(IBFVS_OBJECT_NOISE)
in vec3 v_position_object;
#endif
#else
// The deferred pass's second half (deferred_pass in pass_settings.h): what
// the first half left per pixel of the surface, in place of the varyings.
BINDING(6) uniform sampler2D u_gbuffer0;  // (t(x) unshifted, or kBehind.., from depth, depth)
BINDING(7) uniform sampler2D u_gbuffer1;  // (fwidth(depth), diffuse and flow, v_scalars)
#endif
// What the pass needs of the surface under this pixel: from the varyings,
// or in the deferred pass's second half from the first half's two images.
struct Here {
  bool ahead;        // T(r - v dt) is in front of the eye: t(x) has an image position
  vec2 unshifted;    // t(x) in [0, 1]^2 (else this pixel)
  float from_depth;  // t(x)'s eye depth
  float depth;       // this pixel's eye depth
  float depth_width; // fwidth(depth)
  float diffuse;     // |n . to eye| of the headlight
  vec2 scalars;      // (colour scalar, beta scalar)
  vec2 flow;         // the flow's direction in the last frame's image (unit; 0: none), or in
                     // the deferred pass's first half its displacement in pixels
};
const float kBehind = -1e9;  // a stored t(x) of a point behind the eye
// The flow's direction to 1/4094 of a turn, as a 12-bit code (4095: none).
// The deferred pass's first half keeps it with the headlight's diffuse term
// (12 bits too) in one channel of its second image, as a float's exact
// integer; the single pass takes the same direction (the two passes' F_t
// are equal).
uint direction_code(vec2 flow) {
  return dot(flow, flow) > 1e-12 ? uint(round((atan(flow.y, flow.x) / 6.28318530718 + 0.5) * 4094.0))
                                 : 4095u;
}
vec2 coded_direction(uint code) {
  float angle = (float(code) / 4094.0 - 0.5) * 6.28318530718;
  return code == 4095u ? vec2(0.0) : vec2(cos(angle), sin(angle));
}
Here surface_here() {
  Here h;
#ifdef IBFVS_RESOLVE
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 a = texelFetch(u_gbuffer0, p, 0), b = texelFetch(u_gbuffer1, p, 0);
  h.ahead = a.x > 0.5 * kBehind;
  h.unshifted = h.ahead ? a.xy : gl_FragCoord.xy * u_inverse_size;
  h.from_depth = a.z;
  h.depth = a.w;
  h.depth_width = b.x;
  uint diffuse_flow = uint(b.y);
  h.diffuse = float(diffuse_flow & 4095u) / 4095.0;
  h.flow = coded_direction(diffuse_flow >> 12u);
  h.scalars = b.zw;
#else
  h.ahead = v_from.w > 1e-6;
  h.unshifted = h.ahead ? v_from.xy / v_from.w * 0.5 + 0.5 : gl_FragCoord.xy * u_inverse_size;
  // Eye depths from clip coordinates (no extra varyings: llvmpipe pays for
  // each per pixel): this pixel's from gl_FragCoord, t(x)'s from v_from.
  h.depth = (u_clip_to_depth.x * (2.0 * gl_FragCoord.z - 1.0) + u_clip_to_depth.y) /
            gl_FragCoord.w;
  h.from_depth = u_clip_to_depth.x * v_from.z + u_clip_to_depth.y * v_from.w;
  h.depth_width = fwidth(h.depth);
  vec3 n = normalize(v_normal_eye);
  vec3 to_eye = normalize(-v_position_eye);
  h.diffuse = min(abs(dot(n, to_eye)), 1.0);
#ifdef IBFVS_STREAKS
  h.flow = 0.5 * v_flow / u_inverse_size;
#ifndef IBFVS_GBUFFER
  h.flow = coded_direction(direction_code(h.flow));
#endif
#else
  h.flow = vec2(0.0);  // nothing follows the streaks: the pixel's displacement will do
#endif
#if defined(IBFVS_COLOR_SCALAR) || defined(IBFVS_BETA_SCALAR)
  h.scalars = v_scalars;
#else
  h.scalars = vec2(0.0);
#endif
#endif
  return h;
}
#ifdef IBFVS_GBUFFER
// The deferred pass's first half: the surface, once per drawn fragment,
// cheaply (a fragment of a small triangle shades a whole block on llvmpipe).
layout(location = 0) out vec4 o_gbuffer0;
layout(location = 1) out vec4 o_gbuffer1;
void main() {
  Here h = surface_here();
  o_gbuffer0 = vec4(h.ahead ? h.unshifted : vec2(kBehind), h.from_depth, h.depth);
  uint diffuse = uint(round(clamp(h.diffuse, 0.0, 1.0) * 4095.0));
  o_gbuffer1 = vec4(h.depth_width, float(direction_code(h.flow) * 4096u + diffuse), h.scalars);
}
#else

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
// display pass, once per pixel of the surface (kDisplayFragmentHead); this
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
BINDING(4) uniform sampler2D u_stats;  // 1 x 1: (sum l, sum l^2, count)
#endif
BINDING(0) uniform sampler2D u_previous;  // F_t of the last frame
BINDING(1) uniform sampler2D u_grid;      // w(v_g k + phi_ij), this frame's grid values

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
BINDING(3) uniform sampler2D u_surface_image;  // equirectangular, lon -180..180
uniform vec3 u_image_centre; // centre of the spherical mapping
#endif
#ifdef IBFVS_COLOR_SCALAR
BINDING(2) uniform sampler2D u_color_map;  // 256 x 1
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

)";

const char* const kIbfvsFragmentMain = R"(
#ifdef IBFVS_CUBIC
// Catmull-Rom interpolation of F_t at uv from five bilinear taps: per axis the
// two middle weights are merged into one bilinear tap between their texels,
// and of the 3 x 3 taps that leaves, the four corners (weights w0 w3 and the
// like: at most 1/64 together) are dropped and the rest renormalised, which
// changes no measure of the picture and saves four of llvmpipe's costliest
// reads. Each frame's bilinear resampling blurs F_t by up to a quarter of a
// pixel squared across the flow, and over 1 / alpha frames that adds up; the
// cubic keeps the grain fine. Where a tap has background in its footprint,
// the bilinear value is kept (no inflow through the wider footprint).
vec4 sample_cubic(vec2 uv, vec4 bilinear) {
  vec2 size = vec2(textureSize(u_previous, 0));
  vec2 p = uv * size - 0.5;
  vec2 base = floor(p);
  vec2 f = p - base;
  vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
  vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
  vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
  vec2 w3 = f * f * (-0.5 + 0.5 * f);
  vec2 w12 = w1 + w2;
  vec2 t0 = (base - 0.5) / size, t12 = (base + 0.5 + w2 / w12) / size, t3 = (base + 2.5) / size;
  vec2 tx[3] = vec2[3](t0, t12, t3), wx[3] = vec2[3](w0, w12, w3);
  vec4 sum = vec4(0.0);
  float lowest = 1e30, weights = 0.0;
  const ivec2 taps[5] = ivec2[5](ivec2(1, 0), ivec2(0, 1), ivec2(1, 1), ivec2(2, 1), ivec2(1, 2));
  for (int k = 0; k < 5; ++k) {
    ivec2 ij = taps[k];
    vec4 t = textureLod(u_previous, vec2(tx[ij.x].x, tx[ij.y].y), 0.0);
    lowest = min(lowest, stored_depth(t));
    float w = wx[ij.x].x * wx[ij.y].y;
    sum += w * t;
    weights += w;
  }
  sum /= weights;
#ifdef IBFVS_MONO_TEXTURE
  return lowest > -255.0 ? vec4(clamp(sum.r, 0.0, 1.0), bilinear.g, 0.0, 0.0) : bilinear;
#else
  return lowest > -255.0 ? vec4(clamp(sum.rgb, 0.0, 1.0), bilinear.a) : bilinear;
#endif
}
#endif

void main() {
  Here here = surface_here();
  // A point that was behind the eye has no image position: no advection there.
  bool ahead = here.ahead;
  vec2 unshifted = here.unshifted;
  vec2 texcoord = unshifted - u_texture_shift * u_inverse_size;
  vec4 stored = textureLod(u_previous, texcoord, 0.0);
#ifdef IBFVS_CUBIC
  stored = sample_cubic(texcoord, stored);
#endif
  vec3 previous = stored_value(stored);
  float previous_depth = stored_depth(stored);
#ifdef IBFVS_OBJECT_NOISE
  float g = solid_noise(v_position_object);
#else
  float g = noise(gl_FragCoord.xy - u_noise_shift);
#endif
  // Section 3.5 without the inflow: where t(x) = T(r - v dt) lands outside
  // the last frame's surface (the background holds kNoDepth, so one
  // background texel in the bilinear footprint is enough), outside the
  // image, or on a surface at another depth (an occlusion edge), the image
  // holds nothing of this surface: start from fresh noise instead. The
  // tolerance covers the step off the surface (a few pixels: well under 2%
  // of the depth), the depth's change across a pixel and 16-bit storage. While the image is dragged (3.7) only
  // coverage counts: a depth below -255 has a background texel in its
  // footprint (bilinear weights come in steps of 1/256 at the least).
  float depth = here.depth;
  float from_depth = here.from_depth;
  float tolerance = 0.02 * abs(from_depth) + 2.0 * here.depth_width;
  bool inside = all(greaterThanEqual(texcoord, vec2(0.0))) && all(lessThanEqual(texcoord, vec2(1.0)));
  bool dragged = u_texture_shift != vec2(0.0);
  bool same_surface = ahead && inside &&
                      (dragged ? previous_depth > -255.0
                               : abs(previous_depth - from_depth) <= tolerance ||
                                     previous_depth >= 65000.0);  // kAnyDepth: put in from outside
  vec2 moved = ahead && u_locked == 0 ? gl_FragCoord.xy - unshifted / u_inverse_size : vec2(0.0);
  float moved_length = length(moved);
  // The streaks' direction: the flow's displacement alone (a jump of the
  // surface or the camera's turn is not along them), else this pixel's.
  vec2 flow = ahead && u_locked == 0 ? here.flow : vec2(0.0);
  float flow_length = length(flow);
  vec2 along = flow_length > 1e-6 ? flow / flow_length
             : moved_length > 1e-6 ? moved / moved_length : vec2(0.0);
  vec2 start = texcoord / u_inverse_size;  // t(x) in pixels
#ifdef IBFVS_COMPENSATE
  // The compensated warp (core/texture/display.h): the bilinear sample plus
  // c times its excess over its two neighbours across the flow, c = s v /
  // reach^2 for v the bilinear weights' variance across the flow, which
  // takes back the blur the sample adds there. Sharpening reads the same
  // two neighbours.
  vec2 across_flow = IBFVS_SHARPEN_REACH * vec2(-along.y, along.x);
  vec4 across_a = vec4(0.0), across_b = vec4(0.0);
  if (same_surface && moved_length > 1e-6) {
    across_a = textureLod(u_previous, (start + across_flow) * u_inverse_size, 0.0);
    across_b = textureLod(u_previous, (start - across_flow) * u_inverse_size, 0.0);
    if (stored_depth(across_a) > -255.0 && stored_depth(across_b) > -255.0) {
      vec2 f = fract(start - 0.5);
      float v = dot(f * (1.0 - f), along.yx * along.yx);
      previous = clamp(previous + u_compensation * v *
                                      (previous - 0.5 * (stored_value(across_a) + stored_value(across_b))),
                       0.0, 1.0);
    }
  }
#endif
#ifdef IBFVS_INJECT_ADD
  if (!same_surface && u_locked == 0) previous = vec3(0.0);  // no ink has arrived yet
#else
  if (!same_surface && u_locked == 0) previous = vec3(g);
#endif
#ifdef IBFVS_INJECT_ADD
  vec3 ft = min(previous * (1.0 - u_alpha) + vec3(g), vec3(1.0));
#else
  vec3 ft = mix(previous, vec3(g), u_alpha);  // equation 10
#endif
  if (u_locked != 0) ft = previous;  // a locked texture is only mapped, never changed
#if defined(IBFVS_SHARPEN) && defined(IBFVS_MONO_TEXTURE)
  // Sharpening once per pixel (display_tap): the high-pass of the last
  // frame's F_t at t(x) across this pixel's flow, and that of this frame's
  // noise at x; F_t's high-pass mixes them as equation 10 mixes the values
  // (t carries x's neighbours to t(x)'s, up to the map's slight stretch and
  // turn in one frame). Off the last frame's surface the value is the noise.
  vec2 across = IBFVS_SHARPEN_REACH * vec2(-along.y, along.x);
#ifdef IBFVS_OBJECT_NOISE
  vec3 object_across = dFdx(v_position_object) * across.x + dFdy(v_position_object) * across.y;
#endif
  float high_previous = 0.0, high_noise = 0.0;
  if (moved_length > 1e-6) {
    if (same_surface) {
#ifdef IBFVS_COMPENSATE
      vec4 a = across_a, b = across_b;  // read for the warp, at the same points
#else
      vec4 a = textureLod(u_previous, (start + across) * u_inverse_size, 0.0);
      vec4 b = textureLod(u_previous, (start - across) * u_inverse_size, 0.0);
#endif
      if (stored_depth(a) > -255.0 && stored_depth(b) > -255.0)
        high_previous = previous.r - 0.5 * (stored_value(a).r + stored_value(b).r);
    }
#ifdef IBFVS_OBJECT_NOISE
    high_noise = g - 0.5 * (solid_noise(v_position_object + object_across) +
                            solid_noise(v_position_object - object_across));
#else
    vec2 here = gl_FragCoord.xy - u_noise_shift;
    high_noise = g - 0.5 * (noise(here + across) + noise(here - across));
#endif
  }
#ifdef IBFVS_INJECT_ADD
  float high = (1.0 - u_alpha) * high_previous + high_noise;  // no ink off the last surface
#else
  float high = same_surface ? mix(high_previous, high_noise, u_alpha) : high_noise;
#endif
  if (u_locked != 0) high = high_previous;
#endif
#ifdef IBFVS_MONO_TEXTURE
  o_texture = vec4(ft.r, depth, along);  // the direction the display filter follows
#else
  o_texture = vec4(ft, depth);
#endif
#ifdef IBFVS_TAP_TEXTURE
  o_taps = vec4(encode_tap_value(ft.r + u_sharpen * high), encode_tap_depth(depth, IBFVS_WRITE_TAP_DEPTH),
                0.5 + 0.5 * along);
#endif
#ifdef IBFVS_RECORD_FLOW
  o_flow = moved;
#endif

  // The displayed texture D(F_t), for display only: F_t stays as synthesised.
  vec3 shown = ft;
#if defined(IBFVS_FILTER) || defined(IBFVS_SHARPEN)
  // The display filter's line starts at t(x) in the last frame's F_t, from
  // the value there sharpened (its first tap).
  bool filtered = same_surface && moved_length > 1e-6;
  if (filtered) {
#if defined(IBFVS_SHARPEN) && defined(IBFVS_MONO_TEXTURE)
    shown = previous + u_sharpen * high_previous;
#else
    shown = display_tap(start, previous, along);
#endif
#if defined(IBFVS_FILTER) && !defined(IBFVS_TAP_TEXTURE)
    shown = display_filter(start, along, previous_depth, shown);
#endif
  }
#endif

  // F_s: Blinn-Phong with a headlight, lit from both sides (open meshes).
  float diffuse = here.diffuse;
  float d2 = diffuse * diffuse, d8 = d2 * d2 * d2 * d2, d32 = d8 * d8 * d8 * d8;
  float specular = d32 * d8;  // diffuse^40: half vector = view for a headlight
  vec3 albedo = u_surface_color;
#ifdef IBFVS_SURFACE_IMAGE
  {
    // Longitude and latitude of the direction from the centre, per pixel (no
    // seam where a triangle crosses the date line): +Y north, +Z longitude 0.
    vec3 d = normalize(v_position_object - u_image_centre);
    float lon = atan(d.x, d.z), lat = asin(clamp(d.y, -1.0, 1.0));
    vec2 uv = vec2(lon / 6.28318530718 + 0.5, lat / 3.14159265359 + 0.5);
    albedo = textureGrad(u_surface_image, uv, vec2(0.0), vec2(0.0)).rgb;
  }
#endif
#ifdef IBFVS_COLOR_SCALAR
  if (!isnan(here.scalars.x)) {  // missing data keeps the surface colour
    float t = clamp((here.scalars.x - u_color_range.x) / (u_color_range.y - u_color_range.x), 0.0, 1.0);
    albedo = textureLod(u_color_map, vec2((t * 255.0 + 0.5) / 256.0, 0.5), 0.0).rgb;
  }
#endif
  vec3 shaded = albedo * (0.18 + 0.82 * diffuse) + vec3(0.25 * specular);
  float beta = u_beta;
#ifdef IBFVS_BETA_SCALAR
  beta *= isnan(here.scalars.y)
              ? 0.0
              : clamp((here.scalars.y - u_beta_range.x) / (u_beta_range.y - u_beta_range.x), 0.0, 1.0);
#endif
#if defined(IBFVS_TAP_TEXTURE) && !defined(IBFVS_RESOLVE)
  o_seed = vec4(shown.r, filtered ? previous_depth : kNoFilter, moved);
  o_color = vec4((1.0 - beta) * shaded, beta);
#else
#if defined(IBFVS_TAP_TEXTURE) && defined(IBFVS_FILTER)
  // As the display pass (kDisplayFragmentMain) from the seed.
  if (filtered) shown = display_filter(start, along, previous_depth, vec3(shown.r));
#endif
  float shown_mean = (shown.r + shown.g + shown.b) / 3.0;
#ifdef IBFVS_CONTRAST
#ifdef IBFVS_TAP_TEXTURE
  shown = contrast(shown, contrast_stage(texelFetch(u_stats, ivec2(0), 0).xyz));
#else
  shown = contrast(shown, v_contrast);
#endif
#endif
  o_color = vec4(beta * shown + (1.0 - beta) * shaded, shown_mean);
#endif
}
#endif  // IBFVS_GBUFFER
)";

// The grid pass: one fragment per grid point, G_ij = w(v_g k + phi_ij)
// (equation 8), once per frame instead of four times per pixel.
const char* const kGridFragmentBody = R"(
layout(location = 0) out float o_value;
BINDING(0) uniform sampler2D u_phases;  // phi_ij
uniform float u_noise_time;  // v_g k

void main() {
  ivec2 ij = ivec2(gl_FragCoord.xy);
  o_value = cell_value(ivec3(ij, 0), u_noise_time + texelFetch(u_phases, ij, 0).r);
}
)";

// The statistics pass, after the IBFVS pass: one fragment averages (l, l^2, 1)
// over a grid of sample points on the surface (shifted each frame), l the
// displayed value before the contrast stage, and blends it into a running
// average (weight 0.25, every 4th frame) that the next frames' contrast stage
// reads (no read-back to the CPU).
const char* const kStatsFragmentBody = R"(
layout(location = 0) out vec4 o_stats;
BINDING(0) uniform sampler2D u_texture;  // F_t, depth in the last channel
BINDING(1) uniform sampler2D u_shown;    // F, D(F_t) before the contrast stage in alpha
uniform vec2 u_image_size;
uniform int u_stats_size;
uniform vec2 u_offset;  // in grid cells, in [0, 1): a different sample grid each frame
void main() {
  vec3 sum = vec3(0.0);
  for (int j = 0; j < u_stats_size; ++j)
    for (int i = 0; i < u_stats_size; ++i) {
      ivec2 p = ivec2(floor((vec2(i, j) + u_offset) / float(u_stats_size) * u_image_size));
      vec4 t = texelFetch(u_texture, p, 0);
#ifdef IBFVS_MONO_TEXTURE
      float depth = t.g;
#else
      float depth = t.a;
#endif
      float l = texelFetch(u_shown, p, 0).a;
      if (depth > -255.0) sum += vec3(l, l * l, 1.0);
    }
  // Means, blended into a running average: the ratios stay means whatever
  // the weights, and no surface this frame (0) leaves them as they were.
  o_stats = sum.z > 0.0 ? vec4(sum / sum.z, 0.0) : vec4(0.0);
}
)";

}  // namespace

namespace {

// What differs between the dialects, in this one place: the version line,
// WebGL2's required precisions, and sampler units, which GLSL ES 3.00 cannot
// declare in the shader (layout(binding) is ES 3.10): an ES runtime sets
// them by name (glUniform1i) to the numbers BINDING(n) gives here.
std::string prelude(Dialect dialect) {
  if (dialect == Dialect::Es300)
    return "#version 300 es\n"
           "precision highp float;\nprecision highp int;\nprecision highp sampler2D;\n"
           "#define BINDING(n)\n";
  return "#version 450 core\n#define BINDING(n) layout(binding = n)\n";
}

std::string with_defines(const ShaderFeatures& features, const std::string& body, bool profile,
                         Dialect dialect) {
  std::string source = prelude(dialect);
  const auto define = [&](bool on, const char* name) {
    if (on) source += std::string("#define ") + name + "\n";
  };
  define(features.object_noise, "IBFVS_OBJECT_NOISE");
  define(features.surface_image, "IBFVS_SURFACE_IMAGE");
  define(features.color_scalar, "IBFVS_COLOR_SCALAR");
  define(features.beta_scalar, "IBFVS_BETA_SCALAR");
  define(features.image_step, "IBFVS_IMAGE_STEP");
  define(features.inject_add, "IBFVS_INJECT_ADD");
  define(features.mono_texture, "IBFVS_MONO_TEXTURE");
  define(features.cubic, "IBFVS_CUBIC");
  define(features.compensate, "IBFVS_COMPENSATE");
  if (features.filter_taps > 0)
    source += "#define IBFVS_FILTER " + std::to_string(features.filter_taps) + "\n";
  define(features.contrast, "IBFVS_CONTRAST");
  define(features.record_flow, "IBFVS_RECORD_FLOW");
  define(tap_texture(features), "IBFVS_TAP_TEXTURE");
  define(features.sharpen, "IBFVS_SHARPEN");
  define(features.moving, "IBFVS_MOVING");
  if (features.sharpen || features.compensate)
    source += "#define IBFVS_SHARPEN_REACH " + std::to_string(ibfvs::kSharpenReach) + "\n";
  // The display's work that follows the streaks' direction (the flow's own).
  define(features.sharpen || features.compensate || features.filter_taps > 0, "IBFVS_STREAKS");
  if (profile) source += kProfile;
  return source + body;
}

}  // namespace

unsigned ShaderFeatures::key() const {
  return (object_noise ? 1u : 0u) | (surface_image ? 2u : 0u) | (color_scalar ? 4u : 0u) |
         (beta_scalar ? 8u : 0u) | (image_step ? 16u : 0u) | (inject_add ? 32u : 0u) |
         (mono_texture ? 64u : 0u) | (cubic ? 128u : 0u) | (contrast ? 256u : 0u) |
         (record_flow ? 512u : 0u) | (sharpen ? 1024u : 0u) |
         (static_cast<unsigned>(filter_taps) << 11u) | (compensate ? 1u << 16u : 0u) |
         (moving ? 1u << 17u : 0u);
}

std::string ibfvs_vertex_source(const ShaderFeatures& features, Dialect dialect) {
  return with_defines(features, std::string(kContrast) + kIbfvsVertexBody, false, dialect);
}

std::string ibfvs_fragment_source(const ShaderFeatures& features, Dialect dialect) {
  return with_defines(
      features, std::string(kContrast) + kIbfvsFragmentHead + kDisplayFilter + kIbfvsFragmentMain,
      features.object_noise, dialect);
}

std::string gbuffer_fragment_source(const ShaderFeatures& features, Dialect dialect) {
  return with_defines(features,
                      std::string("#define IBFVS_GBUFFER\n") + kIbfvsFragmentHead + "#endif\n",
                      false, dialect);
}

std::string resolve_fragment_source(const ShaderFeatures& features, Dialect dialect) {
  return with_defines(features,
                      std::string("#define IBFVS_RESOLVE\n") + kContrast + kIbfvsFragmentHead +
                          kDisplayFilter + kIbfvsFragmentMain,
                      features.object_noise, dialect);
}

std::string display_fragment_source(const ShaderFeatures& features, Dialect dialect) {
  return with_defines(
      features,
      std::string(kContrast) + kDisplayFragmentHead + kDisplayFilter + kDisplayFragmentMain, false,
      dialect);
}

std::string grid_vertex_source(Dialect dialect) {
  return prelude(dialect) + kGridVertexBody;
}

std::string display_vertex_source(Dialect dialect) {
  return prelude(dialect) + "#define IBFVS_FAR\n" + kGridVertexBody;
}

std::string stats_fragment_source(bool mono_texture, Dialect dialect) {
  return prelude(dialect) + (mono_texture ? "#define IBFVS_MONO_TEXTURE\n" : "") +
         kStatsFragmentBody;
}

std::string grid_fragment_source(Dialect dialect) {
  return prelude(dialect) + kProfile + kGridFragmentBody;
}

}  // namespace ibfvs::shaders
