// The IBFVS pass's vertex shader (after contrast.glsl): each vertex's
// position now and the point its texture comes from, t = T(r - v dt)
// (equation 13), with the surface's own motion where it moves.
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
// Each pair's screw (core/geometry/rigid_motion.h): the rotation vector and
// the lever from the axis, so that a rigidly moving part turns between its
// steps instead of cutting along chords; zero (an attribute not given): the
// chord.
layout(location = 9) in vec3 a_omega;
layout(location = 10) in vec3 a_lever;
layout(location = 11) in vec3 a_drawn_omega;
layout(location = 12) in vec3 a_drawn_lever;

// (R(phi) - I) l for the unit axis a, as rigid_motion.cpp computes it.
vec3 turned_less_still(vec3 l, vec3 a, float phi) {
  float half_turn = sin(0.5 * phi);
  vec3 across = cross(a, l);
  return sin(phi) * across + 2.0 * half_turn * half_turn * cross(a, across);
}
// interpolate_position (core/geometry/rigid_motion.h): p0 at m = 0, p1 at 1.
vec3 moved_to(vec3 p0, vec3 p1, vec3 omega, vec3 lever, float m) {
  float theta = length(omega);
  if (theta <= 0.0) return mix(p0, p1, m);
  vec3 a = omega / theta;
  vec3 rest = p1 - p0 - turned_less_still(lever, a, theta);
  return p0 + turned_less_still(lever, a, m * theta) + m * rest;
}
// v turned by the rotation vector omega.
vec3 turned_by(vec3 v, vec3 omega) {
  float theta = length(omega);
  return theta > 0.0 ? v + turned_less_still(v, omega / theta, theta) : v;
}
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
BINDING(UNIT_STATS) uniform sampler2D u_stats;  // 1 x 1: (sum l, sum l^2, count)
flat out vec2 v_contrast;
#endif
void main() {
#if defined(IBFVS_CONTRAST) && !defined(IBFVS_TAP_TEXTURE)
  v_contrast = contrast_stage(texelFetch(u_stats, ivec2(0), 0).xyz);
#endif
#ifdef IBFVS_MOVING
  vec3 position = moved_to(a_position, a_position_next, a_omega, a_lever, u_field_mix);
  // interpolate_normal: normalised below, where it is used.
  vec3 normal = turned_by(a_normal, u_field_mix * a_omega) * (1.0 - u_field_mix) +
                turned_by(a_normal_next, (u_field_mix - 1.0) * a_omega) * u_field_mix;
  // The surface's own motion enters the advection as the camera's does:
  // the texture comes from where the last frame drew this point.
  vec3 drawn = moved_to(a_drawn, a_drawn_next, a_drawn_omega, a_drawn_lever, u_drawn_mix);
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
