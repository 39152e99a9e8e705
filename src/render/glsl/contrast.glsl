// Section 3.4's contrast, improved separately: the surface's values moved
// to mean 0.5 and standard deviation u_contrast, with the mean and
// deviation of the last frame's whole surface: steady over time (no
// brightness pumping as with a per-frame min/max stretch).
#ifdef IBFVS_CONTRAST
uniform float u_contrast;
// (mean, gain) from the statistics (sum l, sum l^2, count); gain 0: none yet.
vec2 contrast_stage(vec3 st) {
  if (!(st.z > 0.0)) return vec2(0.0);
  float mean = st.x / st.z;
  float deviation = sqrt(max(st.y / st.z - mean * mean, 0.0));
  return vec2(mean, min(u_contrast / max(deviation, 1e-6), 8.0));
}
vec3 contrast(vec3 shown, vec2 stage) {
  return stage.y > 0.0 ? clamp(0.5 + (shown - stage.x) * stage.y, 0.0, 1.0) : shown;
}
#endif
