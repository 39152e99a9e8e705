// The deferred pass's first half (after ibfvs_fragment_inputs.glsl, with
// IBFVS_GBUFFER): the surface point's t(x), depths, diffuse term, flow
// direction and scalars into two images.
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
