#include "ibfvs/render/shaders.h"

namespace ibfvs::shaders {

namespace {

const char* const kIbfvsVertexBody = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_vector;       // the field at the current time step
layout(location = 4) in vec3 a_vector_next;  // and at the next one (unsteady flow)
layout(location = 3) in vec2 a_scalars;  // (colour scalar, beta scalar)

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
#if defined(IBFVS_COLOR_SCALAR) || defined(IBFVS_BETA_SCALAR)
out vec2 v_scalars;
#endif
out vec3 v_normal_eye;
out vec3 v_position_eye;
#if defined(IBFVS_SURFACE_IMAGE) || defined(IBFVS_OBJECT_NOISE)
out vec3 v_position_object;  // for the spherical image map and the solid noise
#endif

void main() {
  gl_Position = u_view_projection * vec4(a_position, 1.0);
  vec3 v = mix(a_vector, a_vector_next, u_field_mix);
  vec3 step = v * u_dt;
#ifdef IBFVS_IMAGE_STEP
  {  // as image_normalized_step() in core/camera.cpp
    step = vec3(0.0);
    float speed = length(v);
    vec4 a = u_advect_view_projection * vec4(a_position, 1.0);
    vec4 b = u_advect_view_projection * vec4(a_position - v / max(speed, 1e-30) * u_probe, 1.0);
    if (speed > 0.0 && u_dt > 0.0 && a.w > 1e-6 && b.w > 1e-6) {
      float moved = length((a.xy / a.w - b.xy / b.w) * 0.5 * u_size);
      if (moved > 0.0) step = v / speed * (u_probe * min(u_image_step / moved, 50.0));
    }
  }
#endif
  v_from = u_advect_view_projection * vec4(a_position - step, 1.0);
#if defined(IBFVS_COLOR_SCALAR) || defined(IBFVS_BETA_SCALAR)
  v_scalars = a_scalars;
#endif
  v_normal_eye = mat3(u_view) * a_normal;
  v_position_eye = (u_view * vec4(a_position, 1.0)).xyz;
#if defined(IBFVS_SURFACE_IMAGE) || defined(IBFVS_OBJECT_NOISE)
  v_position_object = a_position;
#endif
}
)";

}  // namespace

// The grid pass's vertex shader: one triangle that covers the viewport.
const char* const kGridVertex = R"(#version 450 core
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

namespace {

// The noise time profile w(t), period 1 (equation 8): shared by the grid pass
// and the object-space noise of the IBFVS pass.
const char* const kProfile = R"(
uniform int u_profile;  // 0 square, 1 sawtooth, 2 sine, 3 spike
uniform float u_spike_width;
float profile(float t) {
  float f = t - floor(t);
  if (u_profile == 0) return f < 0.5 ? 1.0 : 0.0;
  if (u_profile == 1) return f;
  if (u_profile == 2) return 0.5 + 0.5 * sin(6.28318530718 * f);
  return f < u_spike_width ? 1.0 : 0.0;
}
)";

// Features a renderer does not use are compiled out (ShaderFeatures), not
// skipped by uniform branches: llvmpipe runs both sides of every branch.
const char* const kIbfvsFragmentBody = R"(
in vec4 v_from;
#if defined(IBFVS_COLOR_SCALAR) || defined(IBFVS_BETA_SCALAR)
in vec2 v_scalars;
#endif
in vec3 v_normal_eye;
in vec3 v_position_eye;
#if defined(IBFVS_SURFACE_IMAGE) || defined(IBFVS_OBJECT_NOISE)
in vec3 v_position_object;
#endif

layout(location = 0) out vec4 o_texture;  // F_t of this frame
layout(location = 1) out vec4 o_color;    // F

layout(binding = 0) uniform sampler2D u_previous;  // F_t of the last frame
layout(binding = 1) uniform sampler2D u_grid;      // w(v_g k + phi_ij), this frame's grid values

uniform float u_alpha;
uniform vec2 u_texture_shift;  // pixels: F_t moved with the mouse for this frame (3.7)
uniform vec2 u_noise_shift;    // pixels: G moved with the mouse, accumulated
uniform float u_beta;
uniform float u_noise_time;  // v_g k
uniform float u_noise_scale; // s
uniform ivec2 u_phase_size;
uniform vec2 u_inverse_size;  // 1 / image size in pixels
uniform vec3 u_surface_color;
uniform int u_locked;        // section 3.7: map F_t, do not update it
#ifdef IBFVS_SURFACE_IMAGE
layout(binding = 3) uniform sampler2D u_surface_image;  // equirectangular, lon -180..180
uniform vec3 u_image_centre; // centre of the spherical mapping
#endif
#ifdef IBFVS_COLOR_SCALAR
layout(binding = 2) uniform sampler2D u_color_map;  // 256 x 1
uniform vec2 u_color_range;  // scalar values at the ends of the map
#endif
#ifdef IBFVS_BETA_SCALAR
uniform vec2 u_beta_range;   // beta is 0 at the first value, u_beta at the second
#endif

#ifndef IBFVS_OBJECT_NOISE
// Equations 6-7: grid values s pixels apart, triangular pulses = bilinear
// interpolation, which the texture unit does: grid point (i, j) at pixel
// (i s, j s) is the centre of texel (i, j). The grid pass wrote this frame's
// values; the texture repeats, so the pattern wraps when shifted (3.7).
float noise(vec2 x) {
  return texture(u_grid, (x / u_noise_scale + 0.5) / vec2(u_phase_size)).r;
}
#else
// Section 3.6 beyond the paper: G on a 3D lattice at the surface point. The
// hash is solid_phase() of noise.cpp, bit for bit.
uniform float u_object_cell;  // lattice spacing in world units
uniform uint u_seed;
float solid_phase(ivec3 i) {
  uint h = uint(i.x) * 73856093u ^ uint(i.y) * 19349663u ^ uint(i.z) * 83492791u ^
           u_seed * 2654435761u;
  uint state = h * 747796405u + 2891336453u;
  h = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  h = (h >> 22u) ^ h;
  return float(h >> 8) / 16777216.0;
}
float solid_noise(vec3 p) {
  vec3 u = p / u_object_cell;
  vec3 fl = floor(u);
  ivec3 i = ivec3(fl);
  vec3 a = u - fl;
  float g = 0.0;
  for (int c = 0; c < 8; ++c) {
    ivec3 d = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    vec3 w3 = mix(1.0 - a, a, vec3(d));
    g += w3.x * w3.y * w3.z * profile(u_noise_time + solid_phase(i + d));
  }
  return g;
}
#endif

void main() {
  // A point that was behind the eye has no image position: no advection there.
  vec2 texcoord = (v_from.w > 1e-6 ? v_from.xy / v_from.w * 0.5 + 0.5
                                   : gl_FragCoord.xy * u_inverse_size) -
                  u_texture_shift * u_inverse_size;
#ifdef IBFVS_MONO_TEXTURE
  vec3 previous = texture(u_previous, texcoord).rrr;
#else
  vec3 previous = texture(u_previous, texcoord).rgb;
#endif
#ifdef IBFVS_OBJECT_NOISE
  float g = solid_noise(v_position_object);
#else
  float g = noise(gl_FragCoord.xy - u_noise_shift);
#endif
#ifdef IBFVS_INJECT_ADD
  vec3 ft = min(previous * (1.0 - u_alpha) + vec3(g), vec3(1.0));
#else
  vec3 ft = mix(previous, vec3(g), u_alpha);  // equation 10
#endif
  if (u_locked != 0) ft = previous;  // a locked texture is only mapped, never changed
  o_texture = vec4(ft, 1.0);

  // F_s: Blinn-Phong with a headlight, lit from both sides (open meshes).
  vec3 n = normalize(v_normal_eye);
  vec3 to_eye = normalize(-v_position_eye);
  float diffuse = min(abs(dot(n, to_eye)), 1.0);
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
  if (!isnan(v_scalars.x)) {  // missing data keeps the surface colour
    float t = clamp((v_scalars.x - u_color_range.x) / (u_color_range.y - u_color_range.x), 0.0, 1.0);
    albedo = texture(u_color_map, vec2((t * 255.0 + 0.5) / 256.0, 0.5)).rgb;
  }
#endif
  vec3 shaded = albedo * (0.18 + 0.82 * diffuse) + vec3(0.25 * specular);
  float beta = u_beta;
#ifdef IBFVS_BETA_SCALAR
  beta *= isnan(v_scalars.y)
              ? 0.0
              : clamp((v_scalars.y - u_beta_range.x) / (u_beta_range.y - u_beta_range.x), 0.0, 1.0);
#endif
  o_color = vec4(beta * ft + (1.0 - beta) * shaded, 1.0);
}
)";

// The grid pass: one fragment per grid point, G_ij = w(v_g k + phi_ij)
// (equation 8), once per frame instead of four times per pixel.
const char* const kGridFragmentBody = R"(
layout(location = 0) out float o_value;
layout(binding = 0) uniform sampler2D u_phases;  // phi_ij
uniform float u_noise_time;  // v_g k

void main() {
  o_value = profile(u_noise_time + texelFetch(u_phases, ivec2(gl_FragCoord.xy), 0).r);
}
)";

}  // namespace

namespace {

std::string with_defines(const ShaderFeatures& features, const char* body, bool profile) {
  std::string source = "#version 450 core\n";
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
  if (profile) source += kProfile;
  return source + body;
}

}  // namespace

unsigned ShaderFeatures::key() const {
  return (object_noise ? 1u : 0u) | (surface_image ? 2u : 0u) | (color_scalar ? 4u : 0u) |
         (beta_scalar ? 8u : 0u) | (image_step ? 16u : 0u) | (inject_add ? 32u : 0u) |
         (mono_texture ? 64u : 0u);
}

std::string ibfvs_vertex_source(const ShaderFeatures& features) {
  return with_defines(features, kIbfvsVertexBody, false);
}

std::string ibfvs_fragment_source(const ShaderFeatures& features) {
  return with_defines(features, kIbfvsFragmentBody, features.object_noise);
}

std::string grid_fragment_source() {
  return std::string("#version 450 core\n") + kProfile + kGridFragmentBody;
}

}  // namespace ibfvs::shaders
