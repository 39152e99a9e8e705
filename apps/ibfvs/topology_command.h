#pragma once
// `ibfvs topology`: the skin-friction topology of a scene's field (the same
// mesh, field, array, block and time options as render): its critical points
// and its separation and attachment lines, written as VTK PolyData with a
// summary line (ibfvs/core/fields/topology.h says how they are found).

namespace CLI {
class App;
}

namespace ibfvs::app {

struct SceneOptions;

/// The command's options: the library's (ibfvs::TopologyOptions).
struct TopologyOptions {
  double scale = 0.05;        ///< ibfvs::TopologyOptions::scale
  double min_strength = 2.0;  ///< ibfvs::TopologyOptions::min_strength
  double min_length = 2.0;    ///< ibfvs::TopologyOptions::min_length
};

void add_topology_options(CLI::App& command, SceneOptions& scene, TopologyOptions& options);

/// Finds, prints the summary and writes the scene's `out` (.vtp; an unsteady
/// scene: one file per step, NAME_0000.vtp ..., and NAME.pvd listing them).
/// Returns the exit status; throws InputError / SettingError.
int run_topology(const SceneOptions& scene, const TopologyOptions& options);

}  // namespace ibfvs::app
