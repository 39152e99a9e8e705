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

/// The scene's options; what counts as a feature is the scene keys'
/// (feature_scale, min_strength, min_length: Scene::topology).
void add_topology_options(CLI::App& command, SceneOptions& scene);

/// Finds, prints the summary and writes the scene's `out` (.vtp; an unsteady
/// scene: one file per step, NAME_0000.vtp ..., and NAME.pvd listing them).
/// Returns the exit status; throws InputError / SettingError.
int run_topology(const SceneOptions& scene);

}  // namespace ibfvs::app
