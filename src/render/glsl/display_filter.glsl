// The display filter and its taps, in the IBFVS pass or (with the tap
// texture) in the display pass.
#ifdef IBFVS_TAP_TEXTURE
BINDING(UNIT_TAPS) uniform sampler2D u_taps;  // the last frame's tap texture
#define IBFVS_TAPS u_taps
// The tap texture in 8 bits a channel (core/texture/display.h, which
// ReferenceIbfvs shares): the sharpened value spread about 0.5, the log eye
// depth between the near and far planes (0: no surface), and the unit
// direction of the displacement as 0.5 + 0.5 d.
uniform float u_tap_value_scale;
// (ln lo, 1 / (ln hi - ln lo)): this frame's map, or the taps' frame's (the
// display pass; the deferred pass's second half reads with it and writes
// with u_new_tap_depth, this frame's).
uniform vec2 u_tap_depth;
#ifdef IBFVS_RESOLVE
uniform vec2 u_new_tap_depth;
#define IBFVS_WRITE_TAP_DEPTH u_new_tap_depth
#else
#define IBFVS_WRITE_TAP_DEPTH u_tap_depth
#endif
float encode_tap_value(float value) { return clamp(0.5 + (value - 0.5) * u_tap_value_scale, 0.0, 1.0); }
float decode_tap_value(float stored) { return 0.5 + (stored - 0.5) / u_tap_value_scale; }
float encode_tap_depth(float depth, vec2 map) {
  return (1.0 + 254.0 * clamp((log(max(depth, 1e-30)) - map.x) * map.y, 0.0, 1.0)) / 255.0;
}
#else
#define IBFVS_TAPS u_previous
#endif
#ifdef IBFVS_FILTER
uniform float u_filter_spacing;        // pixels between taps
uniform float u_filter_weights[16];    // exp(-2 (d / L)^2) of tap k at d = (k + 1) spacing
#endif
#ifdef IBFVS_SHARPEN
uniform float u_sharpen;  // k: each tap plus k (its value - the mean of its neighbours 1.5 px across)
#endif
const float kNoFilter = -65504.0;  // a seed's depth where no line starts

// F_t as stored: the value (grey in one channel, or RGB) and the eye depth;
// a grey F_t also keeps the pixel's displacement in that frame (in pixels),
// which the display filter follows.
#ifdef IBFVS_MONO_TEXTURE
vec3 stored_value(vec4 t) { return t.rrr; }
float stored_depth(vec4 t) { return t.g; }
vec2 stored_flow(vec4 t, vec2 fallback) { return t.ba; }
#else
vec3 stored_value(vec4 t) { return t.rgb; }
float stored_depth(vec4 t) { return t.a; }
vec2 stored_flow(vec4 t, vec2 fallback) { return fallback; }
#endif

#if defined(IBFVS_FILTER) || defined(IBFVS_SHARPEN)
// Sharpening: a value plus k times its excess over its two neighbours 1.5
// pixels across the flow (its high-pass), which counters the blur that the
// frames' resampling leaves across the flow. At 1.5 pixels the gain peaks
// at lines 3 pixels apart, where the picture's streaks are, rather than at
// the pixel grid's own frequency (one pixel): thinner lines and better
// aligned ones (motorbike: A 0.929, W 0.89 px against 0.920, 0.87 at one
// pixel). A grey F_t carries its sharpened value with it (the tap texture,
// made in main()), so a display tap is its value as read; a colour F_t's
// tap at p (pixels) is sharpened here, across the unit direction `along`.
vec3 display_tap(vec2 p, vec3 value, vec2 along) {
#if defined(IBFVS_SHARPEN) && !defined(IBFVS_MONO_TEXTURE)
  vec2 across = IBFVS_SHARPEN_REACH * vec2(-along.y, along.x);
  vec4 a = textureLod(u_previous, (p + across) * u_inverse_size, 0.0);
  vec4 b = textureLod(u_previous, (p - across) * u_inverse_size, 0.0);
  if (stored_depth(a) > -255.0 && stored_depth(b) > -255.0)
    value += u_sharpen * (value - 0.5 * (stored_value(a) + stored_value(b)));
#endif
  return value;
}
#endif

#ifdef IBFVS_FILTER
// A line integral along the flow: a Gaussian exp(-2 (d / L)^2) over taps
// u_filter_spacing apart along the streamline through t(x) in the last
// frame's F_t, which follows the displacement each pixel stored there
// (second-order steps: the heading turned on by half the last turn), so
// the lines stay thin where the flow curves. It reads the last frame's
// F_t carried to this frame, without this frame's fresh noise (alpha G,
// which is not yet smooth along the flow). The line stops where it leaves
// the last frame's surface or meets one at another depth. `shown` is the
// first tap (at t(x): `start`, in pixels), `along` the unit displacement.
// One tap on one side of the line: false where the line stops.
bool filter_tap(inout vec2 p, inout vec2 heading, inout vec2 last, float side, float w,
                float previous_depth, float depth_tolerance, vec2 along, inout vec3 sum,
                inout float weights) {
  vec2 turned = heading + 0.5 * (heading - last);
  p += u_filter_spacing * (dot(turned, turned) > 1e-12 ? normalize(turned) : heading);
  vec4 t = textureLod(IBFVS_TAPS, p * u_inverse_size, 0.0);
#ifdef IBFVS_TAP_TEXTURE
  // Depths as stored (previous_depth too); the background holds none, and
  // its direction 0 stops a line whose footprint it mostly fills.
  if (abs(t.g - previous_depth) > depth_tolerance) return false;
  vec2 f = 2.0 * t.ba - 1.0;
  float fl = length(f);
  if (!(fl > 0.25)) return false;
#else
  if (!(stored_depth(t) > -255.0) || abs(stored_depth(t) - previous_depth) > depth_tolerance)
    return false;
  vec2 f = stored_flow(t, along);
  float fl = length(f);
  if (!(fl > 1e-6)) return false;
#endif
  last = heading;
  heading = side * f / fl;
  if (dot(heading, last) < 0.0) return false;  // a stagnation line: no crossing it
#ifdef IBFVS_TAP_TEXTURE
  sum += w * decode_tap_value(t.r);
#else
  sum += w * display_tap(p, stored_value(t), heading);
#endif
  weights += w;
  return true;
}

vec3 display_filter(vec2 start, vec2 along, float previous_depth, vec3 shown) {
  vec3 sum = shown;
  float weights = 1.0;
#ifdef IBFVS_TAP_TEXTURE
  float depth_tolerance = (0.05 * 254.0 * u_tap_depth.y + 1.0) / 255.0;  // tap_depth_tolerance()
  previous_depth = encode_tap_depth(previous_depth, u_tap_depth);
#else
  float depth_tolerance = 0.05 * abs(previous_depth);
#endif
  // Both sides in one loop, a tap of each per step: llvmpipe runs a loop
  // until its last lane stops, and one loop of two taps costs less than two
  // loops of one (the default look's frame about 5-10% shorter).
  vec2 pa = start, ha = -along, la = ha, pb = start, hb = along, lb = hb;
  bool a = true, b = true;
  for (int k = 0; k < IBFVS_FILTER; ++k) {  // taps per side, a compile-time constant
    float w = u_filter_weights[k];
    if (a) a = filter_tap(pa, ha, la, -1.0, w, previous_depth, depth_tolerance, along, sum, weights);
    if (b) b = filter_tap(pb, hb, lb, 1.0, w, previous_depth, depth_tolerance, along, sum, weights);
    if (!a && !b) break;
  }
  return sum / weights;
}
#endif
