#pragma once
// `ibfvs quality`: the picture-quality measures of docs/quality.md for any
// scene (the same options as render): alignment with the flow, background
// inflow, the pattern's speed against the flow's, flicker and contrast.

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace ibfvs::app {

struct SceneOptions;

struct QualityOptions {
  int warmup = 120;  ///< frames before measuring
  /// Instead of a scene: a picture from another tool (ParaView's Surface LIC)
  /// of a flow that turns about the view axis, measured for alignment and
  /// contrast; the surface is every pixel not of the corner pixel's colour.
  std::string png;
  std::vector<float>
      centre;  ///< the rotation's centre in pixels (x right, y down); default the middle
  /// With png: the true flow direction per pixel in the same view instead of
  /// a rotation (a direction-coded picture: red, green = 0.5 + 0.5 x, y of the
  /// unit direction, x right and y up; blue 255 where it is defined, 0 not).
  std::string direction;
  /// Measure the picture as shown (the scene's beta, shading, background)
  /// rather than the texture alone with beta 1 and a red background.
  bool shown = false;
};

void add_quality_options(CLI::App& command, SceneOptions& scene, QualityOptions& options);

/// Measures and prints; returns the exit status.
int run_quality(const SceneOptions& scene, const QualityOptions& options);

}  // namespace ibfvs::app
