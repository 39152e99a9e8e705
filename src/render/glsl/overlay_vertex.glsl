// The topology overlay (topology_overlay.h): quads extruded in the image.
// Shapes: 0 a line's segment (point: this end, other: the other end,
// corner: (cap, side)); 1-6 a critical point's glyph by kind (point: its
// centre, corner: -1..1); 7 a legend rectangle and 11-16 a legend glyph,
// both in pixels from the bottom left (point.xy).
layout(location = 0) in vec3 a_point;
layout(location = 1) in vec3 a_other;
layout(location = 2) in vec2 a_corner;
layout(location = 3) in vec3 a_colour;
layout(location = 4) in float a_shape;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform vec2 u_viewport;     // pixels
uniform float u_line_width;  // pixels
uniform float u_glyph;       // pixels across
uniform float u_lift;        // the fraction of the eye distance towards the eye
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
  if (shape >= 7) {  // the legend: pixels, in front of everything
    gl_Position = vec4(a_point.xy / u_viewport * 2.0 - 1.0, -1.0, 1.0);
    return;
  }
  vec2 half_pixel = 2.0 / u_viewport;  // NDC per pixel
  if (shape == 0) {
    vec4 c = lifted(a_point), o = lifted(a_other);
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
  vec4 c = lifted(a_point);
  c.xy += a_corner * 0.5 * u_glyph * half_pixel * c.w;
  gl_Position = c;
}
