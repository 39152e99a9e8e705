// The display pass, with the tap texture: D(F_t) and F once per pixel of
// the surface, drawn after the IBFVS pass over the viewport with the depth
// test keeping the surface's pixels. The display filter is most of a frame
// on llvmpipe, and in the IBFVS pass it ran for every fragment drawn (small
// triangles shade whole blocks of pixels, and hidden ones shade too).
BINDING(UNIT_START) uniform sampler2D u_start;  // (the first tap, t(x)'s depth or kNoFilter, displacement)
BINDING(UNIT_BASE) uniform sampler2D u_base;   // ((1 - beta) F_s, beta)
BINDING(UNIT_TAPS_NOW) uniform sampler2D u_taps_now;  // this frame's taps: the flow's direction at each pixel
#ifdef IBFVS_CONTRAST
BINDING(UNIT_STATS) uniform sampler2D u_stats;  // 1 x 1: (sum l, sum l^2, count)
#endif
uniform vec2 u_inverse_size;   // 1 / image size in pixels
uniform vec2 u_texture_shift;  // pixels: F_t moved with the mouse for this frame (3.7)
// F; its alpha holds D(F_t) before the contrast stage, for the statistics.
layout(location = 0) out vec4 o_color;
