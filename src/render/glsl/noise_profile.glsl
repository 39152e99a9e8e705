// The noise time profile w(t), period 1 (equation 8): shared by the grid pass
// and the object-space noise of the IBFVS pass.
uniform int u_profile;  // 0 square, 1 sawtooth, 2 sine, 3 spike, 4 random
uniform float u_spike_width;
uniform uint u_seed;
// solid_phase() of noise.cpp, bit for bit: a PCG step of the lattice point.
float solid_phase(ivec3 i, uint seed) {
  uint h = uint(i.x) * 73856093u ^ uint(i.y) * 19349663u ^ uint(i.z) * 83492791u ^
           seed * 2654435761u;
  uint state = h * 747796405u + 2891336453u;
  h = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  h = (h >> 22u) ^ h;
  return float(h >> 8) / 16777216.0;
}
// cell_noise_value() of noise.cpp: w(t), or for the random profile a new
// value per period eased from the last one.
float cell_value(ivec3 cell, float t) {
  float n = floor(t), f = t - n;
  if (u_profile == 4) {
    uint c = uint(int(n));
    float a = solid_phase(cell, u_seed + c * 0x9E3779B9u);
    float b = solid_phase(cell, u_seed + (c + 1u) * 0x9E3779B9u);
    return a + (b - a) * (0.5 - 0.5 * cos(3.14159265359 * f));
  }
  if (u_profile == 0) return f < 0.5 ? 1.0 : 0.0;
  if (u_profile == 1) return f;
  if (u_profile == 2) return 0.5 + 0.5 * sin(6.28318530718 * f);
  return f < u_spike_width ? 1.0 : 0.0;
}
