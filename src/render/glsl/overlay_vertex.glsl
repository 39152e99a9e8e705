// The topology overlay (topology_overlay.h): quads extruded in the image.
// Shapes: 0 a line's segment (point: this end, other: the other end,
// corner: (cap, side)); 1-6 a critical point's glyph by kind (point: its
// centre, corner: -1..1); 7 a legend rectangle and 11-16 a legend glyph,
// both in pixels from the bottom left (point.xy). Between two steps of a
// series (topology_morph.h) point and other move to point_to and other_to
// as u_mix goes from 0 to 1, along the surface (bulging by point_bulge and
// other_bulge halfway: FeatureMorph::at); span 1 is drawn only while u_mix < 0.5, span
// 2 only from 0.5 on (a feature that does not persist).
layout(location = 0) in vec3 a_point;
layout(location = 1) in vec3 a_other;
layout(location = 2) in vec2 a_corner;
layout(location = 3) in vec3 a_colour;
layout(location = 4) in float a_shape;
layout(location = 5) in vec3 a_point_to;
layout(location = 6) in vec3 a_other_to;
layout(location = 7) in vec3 a_point_bulge;
layout(location = 8) in vec3 a_other_bulge;
layout(location = 9) in float a_span;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform vec2 u_viewport;     // pixels
uniform float u_line_width;  // pixels
uniform float u_glyph;       // pixels across
uniform float u_lift;        // the fraction of the eye distance towards the eye
uniform float u_mix;         // the fraction of the step played
out vec3 v_colour;
out vec2 v_local;
flat out int v_shape;

vec4 lifted(vec3 p) {
  vec4 eye = u_view * vec4(p, 1.0);
  eye.xyz *= 1.0 - u_lift;
  return u_projection * eye;
}

void main() {
  int shape = int(a_shape + 0.5);
  v_shape = shape;
  v_colour = a_colour;
  v_local = a_corner;
  int span = int(a_span + 0.5);
  if ((span == 1 && u_mix >= 0.5) || (span == 2 && u_mix < 0.5)) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside: the quad is clipped away
    return;
  }
  float arc = 4.0 * u_mix * (1.0 - u_mix);
  vec3 point = mix(a_point, a_point_to, u_mix) + arc * a_point_bulge;
  vec3 other = mix(a_other, a_other_to, u_mix) + arc * a_other_bulge;
  if (shape >= 7) {  // the legend: pixels, in front of everything
    gl_Position = vec4(a_point.xy / u_viewport * 2.0 - 1.0, -1.0, 1.0);
    return;
  }
  vec2 half_pixel = 2.0 / u_viewport;  // NDC per pixel
  if (shape == 0) {
    vec4 c = lifted(point), o = lifted(other);
    vec2 d = (o.xy / o.w - c.xy / c.w) / half_pixel;  // pixels
    float len = length(d);
    d = len > 1e-6 ? d / len : vec2(1.0, 0.0);
    vec2 n = vec2(-d.y, d.x);
    float h = 0.5 * u_line_width;
    c.xy += (n * a_corner.y * h - d * h) * half_pixel * c.w;  // and a cap of half the width
    gl_Position = c;
    v_local = vec2(0.0, a_corner.y);
    return;
  }
  vec4 c = lifted(point);
  c.xy += a_corner * 0.5 * u_glyph * half_pixel * c.w;
  gl_Position = c;
}
