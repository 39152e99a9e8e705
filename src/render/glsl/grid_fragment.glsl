// The grid pass: one fragment per grid point, G_ij = w(v_g k + phi_ij)
// (equation 8), once per frame instead of four times per pixel.
layout(location = 0) out float o_value;
BINDING(UNIT_PHASES) uniform sampler2D u_phases;  // phi_ij
uniform float u_noise_time;  // v_g k

void main() {
  ivec2 ij = ivec2(gl_FragCoord.xy);
  o_value = cell_value(ivec3(ij, 0), u_noise_time + texelFetch(u_phases, ij, 0).r);
}
