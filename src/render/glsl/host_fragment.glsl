// Copies F and the surface's depth into a host's framebuffer (ParaView's),
// the background left as the host drew it; with u_interior 1 not at the
// surface's silhouettes. Desktop GL only (host_fragment_source).
BINDING(UNIT_OUTPUT) uniform sampler2D u_output;
BINDING(UNIT_DEPTH) uniform sampler2D u_depth;
uniform ivec2 u_origin;  // the host viewport's lower left corner
uniform int u_interior;  // 1: not at the silhouettes (drawing again over FXAA)
out vec4 o_color;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - u_origin;
  float d = texelFetch(u_depth, p, 0).r;
  if (d >= 1.0) discard;  // no surface: the host's background and other objects stay
  if (u_interior == 1) {
    // The 3x3 neighbourhood but two corners in two gathers (clamped at the
    // image's edges): the texels about the pixel's lower left and upper
    // right corners.
    vec2 size = vec2(textureSize(u_depth, 0));
    vec4 a = textureGather(u_depth, vec2(p) / size);
    vec4 b = textureGather(u_depth, vec2(p + 1) / size);
    vec4 n = max(a, b);
    if (max(max(n.x, n.y), max(n.z, n.w)) >= 1.0) discard;  // a silhouette: FXAA's stays
  }
  o_color = vec4(texelFetch(u_output, p, 0).rgb, 1.0);
  gl_FragDepth = d;
}
