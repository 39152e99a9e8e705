// The statistics pass, after the IBFVS pass: one fragment averages (l, l^2, 1)
// over a grid of sample points on the surface (shifted each frame), l the
// displayed value before the contrast stage, and blends it into a running
// average (weight 0.25, every 4th frame) that the next frames' contrast stage
// reads (no read-back to the CPU).
layout(location = 0) out vec4 o_stats;
BINDING(UNIT_TEXTURE) uniform sampler2D u_texture;  // F_t, depth in the last channel
BINDING(UNIT_SHOWN) uniform sampler2D u_shown;    // F, D(F_t) before the contrast stage in alpha
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
