#pragma once
// The picture-quality measures of docs/quality.md, on any prepared scene:
// alignment with the flow, background inflow, the pattern's speed against
// the flow's, the flicker along the flow and the RMS contrast, all on the
// texture as displayed (beta 1).

#include "ibfvs/core/image/image_analysis.h"
#include "ibfvs/core/scene/scene_prep.h"

namespace ibfvs {

struct QualityReport {
  int width = 0, height = 0, warmup = 0;
  double coverage = 0.0;         ///< fraction of the image the surface covers
  double alignment = 0.0;        ///< A (flow_alignment), 0.5 isotropic, 1 perfect streaks
  double streak_width = 0.0;     ///< W (streak_width) in pixels: thin lines about 0.8
  double grain = 0.0;            ///< Z (grain_along): grain along the lines, LIC about 0.1
  double red_inflow = 0.0;       ///< surface pixels tinted by the red background, fraction
  PatternMotion lag8, lag16;     ///< the pattern's motion over 8 and 16 frames
  double carried = 0.0;          ///< frame-to-frame correlation along the flow (flicker: low)
  double contrast = 0.0;         ///< RMS contrast, mean over the measured frames
  double contrast_spread = 0.0;  ///< its standard deviation over them, relative to the mean
  double frame_ms = 0.0;         ///< mean time per frame over the measured frames (with read-back)
};

/// Runs the scene with beta 1 and a red background (B = 1,0,0) for `warmup`
/// frames and 17 more, reading the displayed texture and the flow of each of
/// the 17. The flow is taken as steady over them and the camera as still
/// (orbit and lock are switched off). `shown`: the picture as the scene shows
/// it instead (its beta, shading and background; red_inflow is then NaN), A
/// and W on its luminance. Needs a current OpenGL 4.5 context.
QualityReport measure_quality(PreparedScene scene, int warmup = 120, bool shown = false);

}  // namespace ibfvs
