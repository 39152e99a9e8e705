// The IBFVS pass's fragment inputs: the varyings, or (IBFVS_RESOLVE) the
// deferred pass's two images, and surface_here(), what a fragment knows of
// its surface point. Features a renderer does not use are compiled out
// (ShaderFeatures), not skipped by uniform branches: llvmpipe runs both
// sides of every branch.
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
BINDING(UNIT_GBUFFER0) uniform sampler2D u_gbuffer0;  // (t(x) unshifted, or kBehind.., from depth, depth)
BINDING(UNIT_GBUFFER1) uniform sampler2D u_gbuffer1;  // (fwidth(depth), diffuse and flow, v_scalars)
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
