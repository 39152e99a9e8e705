#pragma once
// The plan of a frame: its passes in the order they run, and for each pass
// the image every sampler of its programs reads (the units they are bound
// to are the units' table's, texture_units.h). IbfvsRenderer binds each
// pass's images by it, and the page carries it in its header ("plan") for
// its runtime, which runs the passes in that order and binds by it too: the
// frame is described once.
//
// Images: phases (phi_ij), grid (G of the frame), texture.last and
// texture.now (F_t before and after the frame), taps.last and taps.now
// (their tap textures), color_map, surface_image, stats (the running
// statistics), gbuffer0 and gbuffer1 (the deferred pass's first half's),
// seed and base (what the IBFVS pass leaves the display pass), output (F)
// and depth (the surface's).

#include <span>
#include <string_view>

namespace ibfvs {

/// One sampler of a pass and the image bound to it.
struct PlannedRead {
  std::string_view sampler;  ///< the GLSL name (u_previous, ...)
  int unit;                  ///< its unit (texture_units.h)
  std::string_view image;    ///< the image bound there
};

/// One pass of the frame.
struct PlannedPass {
  std::string_view name;  ///< grid, ibfvs, resolve, display, stats, host
  /// Where a frame runs it: always; "deferred" (the IBFVS pass split in two),
  /// "taps" (a tap texture), "contrast" (every kStatsEvery frames with the
  /// contrast stage on), "host" (drawn into a host's framebuffer, after the
  /// frame).
  std::string_view when;
  std::span<const PlannedRead> reads;
};

/// Every pass, in the order a frame runs them.
[[nodiscard]] std::span<const PlannedPass> frame_plan();
/// The pass named `name` (throws std::out_of_range for another name).
[[nodiscard]] const PlannedPass& planned_pass(std::string_view name);

}  // namespace ibfvs
