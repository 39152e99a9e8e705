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

#include "ibfvs/render/shader_features.h"

namespace ibfvs {

/// The frame's constants, for the renderer and the page alike.
namespace frame {
inline constexpr int kStatsEvery = 4;         ///< frames between statistics passes
inline constexpr float kStatsWeight = 0.25f;  ///< of each pass in the running average
/// The depth F_t stores where no surface was drawn.
inline constexpr float kNoDepth = -65504.0f;
/// The depth of a texture put in from outside (random cells): taken as on
/// whatever surface the next frame finds there.
inline constexpr float kAnyDepth = 65504.0f;
}  // namespace frame

/// One sampler of a pass and the image bound to it.
struct PlannedRead {
  std::string_view sampler;  ///< the GLSL name (u_previous, ...)
  int unit;                  ///< its unit (texture_units.h)
  std::string_view image;    ///< the image bound there
};

/// One pass of the frame.
struct PlannedPass {
  std::string_view name;  ///< grid, ibfvs, resolve, display, stats, host
  /// When a frame runs it (pass_runs): "" always; "image_noise" (the noise
  /// on the image-space grid, not the solid noise); "deferred" (the IBFVS
  /// pass split in two); "taps" (a tap texture); "contrast" (every
  /// kStatsEvery frames with the contrast stage on); "host" (drawn into a
  /// host's framebuffer, after the frame).
  std::string_view when;
  std::span<const PlannedRead> reads;
};

/// What a pass's `when` is decided by: the features of the look (its
/// programs), and the frame's number.
struct PassFacts {
  bool image_noise = true;  ///< the noise on the image-space grid
  bool deferred = false;    ///< the IBFVS pass in two halves
  bool taps = false;        ///< a tap texture, and the display pass
  bool contrast = false;    ///< the contrast stage
  int frame = 0;
};
/// The facts of a look with these features (deferred: where the renderer
/// splits the pass; the page never does).
[[nodiscard]] PassFacts pass_facts(const shaders::ShaderFeatures& features, bool deferred,
                                   int frame);
/// Whether a frame runs a pass whose `when` is `when`: the one rule the
/// renderer's frame and the page (runtime.ts: runs, over the header's look
/// facts) both follow. A host's pass runs after the frame, never in it.
[[nodiscard]] bool pass_runs(std::string_view when, const PassFacts& facts);

/// Every pass, in the order a frame runs them.
[[nodiscard]] std::span<const PlannedPass> frame_plan();
/// The pass named `name` (throws std::out_of_range for another name).
[[nodiscard]] const PlannedPass& planned_pass(std::string_view name);

}  // namespace ibfvs
