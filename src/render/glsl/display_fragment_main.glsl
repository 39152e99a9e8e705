// The display pass's main(): the filter from the seed the IBFVS pass
// left, the contrast stage, and F.
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 seed = texelFetch(u_start, p, 0);
  vec4 base = texelFetch(u_base, p, 0);
  vec3 shown = vec3(seed.x);
#ifdef IBFVS_FILTER
  vec2 moved = seed.ba;  // as the IBFVS pass wrote it: t(x) = x - moved
  float moved_length = length(moved);
  // The streaks' direction as the IBFVS pass took it (the flow's own,
  // without the surface's or the camera's motion), stored with this frame's taps.
  vec2 along = 2.0 * texelFetch(u_taps_now, p, 0).ba - 1.0;
  float along_length = length(along);
  if (seed.y > -255.0 && moved_length > 0.0)
    shown = display_filter(gl_FragCoord.xy - moved - u_texture_shift,
                           along_length > 0.25 ? along / along_length : moved / moved_length,
                           seed.y, shown);
#endif
  float shown_mean = (shown.r + shown.g + shown.b) / 3.0;
#ifdef IBFVS_CONTRAST
  shown = contrast(shown, contrast_stage(texelFetch(u_stats, ivec2(0), 0).xyz));
#endif
  o_color = vec4(base.a * shown + base.rgb, shown_mean);
}
