// The grid pass's vertex shader: one triangle that covers the viewport; the
// display pass's lies on the far plane (IBFVS_FAR), so that a depth test of
// GREATER passes where the IBFVS pass drew the surface and nowhere else.
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
#ifdef IBFVS_FAR
  gl_Position = vec4(p * 2.0 - 1.0, 1.0, 1.0);
#else
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
#endif
}
