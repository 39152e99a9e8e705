#include "ibfvs/topology_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "ibfvs/core/fields/topology.h"
#include "ibfvs/core/fields/topology_layout.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"
#include "ibfvs/render_command.h"

namespace ibfvs::app {
namespace fs = std::filesystem;

void add_topology_options(CLI::App& command, SceneOptions& scene) {
  add_scene_options(command, scene);
}

namespace {

// The topology of one step: found on the step's surface (its ids carried
// on from the step before, if any), its summary printed, written to `path`.
FlowTopology one_step(const TriMesh& mesh, std::span<const glm::vec3> field,
                      const ibfvs::TopologyOptions& options, const FlowTopology* before,
                      int& next_id, const std::string& path, const std::string& what, bool quiet) {
  const auto t0 = std::chrono::steady_clock::now();
  FlowTopology topology = find_topology(mesh, field, options);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (before)
    carry_ids(*before, topology, next_id, 2.0 * topology.lines.scale);
  else
    next_id = static_cast<int>(topology.critical.points.size() + topology.lines.lines.size());
  const std::string summary = topology_summary(topology, mesh);
  write_topology_vtp(topology_layout(topology, summary), path);
  if (!quiet)
    std::printf("ibfvs: %s: %s (%zu triangles, %.0f ms); wrote %s\n", what.c_str(), summary.c_str(),
                mesh.triangles.size(), ms, path.c_str());
  return topology;
}

}  // namespace

int run_topology(const SceneOptions& scene_options) {
  Scene scene = scene_from_command_line(scene_options);
  if (scene.out.empty()) throw InputError("--out: give the .vtp file to write (-o OUT.vtp)");
  if (lower_extension(scene.out) != ".vtp")
    throw InputError("--out: the topology is written as VTK PolyData, a .vtp file, got '" +
                     scene.out + "'");
  if (same_file(scene.out, scene.mesh))
    throw InputError("--out: " + scene.out + " is the input mesh; writing it would destroy it");
  ensure_parent(scene.out, "--out");
  const std::string out = scene.out;
  scene.out.clear();  // prepare_scene checks a render's output, not ours
  const PreparedScene prepared = prepare_scene(scene);
  for (const std::string& w : prepared.warnings)
    std::fprintf(stderr, "ibfvs: warning: %s\n", w.c_str());
  const ibfvs::TopologyOptions& lines = scene.topology;
  int next_id = 0;
  if (prepared.step_count < 2) {
    one_step(*prepared.mesh, prepared.field, lines, nullptr, next_id, out, prepared.mesh_name,
             scene.quiet);
    return 0;
  }
  // One file a step beside a .pvd that ParaView plays as a series.
  const fs::path base = fs::path(out).replace_extension();
  std::string pvd =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  std::optional<FlowTopology> before;
  for (std::size_t k = 0; k < prepared.step_count; ++k) {
    char suffix[32];
    std::snprintf(suffix, sizeof suffix, "_%04zu.vtp", k);
    const fs::path file = base.string() + suffix;
    const StepData step = k == 0 ? StepData{} : prepared.step_data(k);
    const std::span<const glm::vec3> field = k == 0 ? std::span<const glm::vec3>(prepared.field)
                                                    : std::span<const glm::vec3>(step.field);
    before =
        one_step(step_surface(prepared, step), field, lines, before ? &*before : nullptr, next_id,
                 file.string(), prepared.mesh_name + " step " + std::to_string(k), scene.quiet);
    pvd += "    <DataSet timestep=\"" + std::to_string(k) + "\" file=\"" +
           file.filename().string() + "\"/>\n";
  }
  pvd += "  </Collection>\n</VTKFile>\n";
  const std::string pvd_path = base.string() + ".pvd";
  std::ofstream file(pvd_path, std::ios::binary);
  if (!(file << pvd) || !file.flush()) throw InputError(pvd_path + ": cannot be written");
  if (!scene.quiet)
    std::printf("ibfvs: wrote %s (%zu steps)\n", pvd_path.c_str(), prepared.step_count);
  return 0;
}

}  // namespace ibfvs::app
