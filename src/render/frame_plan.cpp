#include "ibfvs/render/frame_plan.h"

#include <stdexcept>
#include <string>

#include "ibfvs/render/texture_units.h"

namespace ibfvs {
namespace {

using namespace units;

// The IBFVS pass, in one piece or as its deferred first half.
constexpr PlannedRead kIbfvsReads[] = {
    {"u_previous", kPrevious, "texture.last"},
    {"u_taps", kTaps, "taps.last"},
    {"u_grid", kGrid, "grid"},
    {"u_color_map", kColorMap, "color_map"},
    {"u_surface_image", kSurfaceImage, "surface_image"},
    {"u_stats", kStats, "stats"},
};
// Its second half reads what the first left, beside the same images (no
// surface image: deferred_pass leaves that pass in one piece).
constexpr PlannedRead kResolveReads[] = {
    {"u_previous", kPrevious, "texture.last"},
    {"u_taps", kTaps, "taps.last"},
    {"u_grid", kGrid, "grid"},
    {"u_color_map", kColorMap, "color_map"},
    {"u_stats", kStats, "stats"},
    {"u_gbuffer0", kGBuffer0, "gbuffer0"},
    {"u_gbuffer1", kGBuffer1, "gbuffer1"},
};
constexpr PlannedRead kGridReads[] = {{"u_phases", kPhases, "phases"}};
constexpr PlannedRead kDisplayReads[] = {
    {"u_start", kStart, "seed"},          {"u_base", kBase, "base"},
    {"u_stats", kStats, "stats"},         {"u_taps", kTaps, "taps.last"},
    {"u_taps_now", kTapsNow, "taps.now"},
};
constexpr PlannedRead kStatsReads[] = {{"u_texture", kTexture, "texture.now"},
                                       {"u_shown", kShown, "output"}};
constexpr PlannedRead kHostReads[] = {{"u_output", kOutput, "output"},
                                      {"u_depth", kDepth, "depth"}};

constexpr PlannedPass kPlan[] = {
    {"grid", "image_noise", kGridReads},    {"ibfvs", "", kIbfvsReads},
    {"resolve", "deferred", kResolveReads}, {"display", "taps", kDisplayReads},
    {"stats", "contrast", kStatsReads},     {"host", "host", kHostReads},
};

}  // namespace

PassFacts pass_facts(const shaders::ShaderFeatures& f, bool deferred, int frame) {
  return {!f.object_noise, deferred, shaders::tap_texture(f), f.contrast, frame};
}

bool pass_runs(std::string_view when, const PassFacts& f) {
  if (when.empty()) return true;
  if (when == "image_noise") return f.image_noise;
  if (when == "deferred") return f.deferred;
  if (when == "taps") return f.taps;
  if (when == "contrast") return f.contrast && f.frame % frame::kStatsEvery == 0;
  return false;  // host: after the frame
}

std::span<const PlannedPass> frame_plan() {
  return kPlan;
}

const PlannedPass& planned_pass(std::string_view name) {
  for (const PlannedPass& p : kPlan)
    if (p.name == name) return p;
  throw std::out_of_range("no pass '" + std::string(name) + "' in the frame plan");
}

}  // namespace ibfvs
