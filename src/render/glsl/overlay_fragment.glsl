// The topology overlay's colours: lines with a dark rim, glyphs by kind
// (saddle: a diamond; nodes: discs; foci: rings; centre: a square), each
// with a dark outline so that it reads on any texture.
in vec3 v_colour;
in vec2 v_local;
flat in int v_shape;
layout(location = 0) out vec4 o_colour;

void main() {
  vec3 colour = v_colour;
  int kind = v_shape >= 11 ? v_shape - 10 : v_shape;
  if (v_shape == 0) {
    if (abs(v_local.y) > 0.7) colour *= 0.35;
  } else if (v_shape != 7) {
    vec2 p = v_local;
    float r = kind == 1 ? abs(p.x) + abs(p.y) : kind == 6 ? max(abs(p.x), abs(p.y)) : length(p);
    if (r > 1.0) discard;
    if (r > 0.7 || ((kind == 4 || kind == 5) && r < 0.3)) colour = vec3(0.05);
  }
  o_colour = vec4(colour, 1.0);
}
