// The first steps of a preparation: the settings, the mesh, a series' steps.
#include <filesystem>

#include "ibfvs/core/mesh/gpu_prep.h"
#include "steps.h"

namespace ibfvs::prep {

namespace fs = std::filesystem;

void settings(Preparation& c) {
  const Scene& s = c.s;
  PreparedScene& p = c.p;
  p.scene = s;
  p.width = s.width;
  p.height = s.height;
  p.frames = s.frames;
  p.lock_at = s.lock_at;

  RenderSettings base;
  base.width = s.width;
  base.height = s.height;
  p.settings = scene_settings(s, base);

  std::optional<FieldSpec>& field_spec = c.field_spec;
  field_spec = s.field;
  if (!field_spec && !s.elements.empty()) field_spec = FieldSpec::parse("elements");
  c.time_first = s.time ? s.time->first : 0;
  if (field_spec) {
    for (const FlowElement& e : s.elements) field_spec->elements.push_back(e);
    field_spec->time = c.time_first;
  }
}

void load(Preparation& c) {
  const Scene& s = c.s;
  PreparedScene& p = c.p;
  const bool in_memory = c.given.has_value();
  LoadedMesh& loaded = c.loaded;
  loaded = in_memory
               ? std::move(*c.given)
               : for_key("mesh", [&] { return load_mesh(s.mesh, s.subdivide, true, s.blocks); });
  for (const std::string& w : loaded.warnings) p.warnings.push_back(w);
  c.mesh = std::make_shared<TriMesh>(std::move(loaded.mesh));
  p.demo = loaded.demo;
  p.mesh_name = loaded.demo || in_memory ? loaded.name : fs::path(s.mesh).filename().string();
  // Messages about the mesh's data name the file as given.
  c.label = loaded.demo || in_memory ? p.mesh_name : s.mesh;
}

void series(Preparation& c) {
  const Scene& s = c.s;
  PreparedScene& p = c.p;
  LoadedMesh& loaded = c.loaded;
  TriMesh& mesh = *c.mesh;
  const std::string& mesh_label = c.label;
  std::optional<FieldSpec>& field_spec = c.field_spec;
  const bool series = c.series = !loaded.step_times.empty();
  std::size_t& series_first = c.series_first;
  std::size_t& series_last = c.series_last;
  if (series) {
    const std::size_t count = loaded.step_times.size();
    if (s.subdivide > 0)
      throw SettingError("subdivide", mesh_label + ": a series (" + std::to_string(count) +
                                          " steps) cannot be subdivided");
    if (!s.field_steps.empty())
      throw SettingError("field_step", mesh_label + ": is a series already");
    series_first = s.time ? s.time->first : 0;
    series_last = s.time ? s.time->last : count - 1;
    if (series_last >= count)
      throw SettingError("time", mesh_label + ": has " + std::to_string(count) + " steps (0.." +
                                     std::to_string(count - 1) + "), asked for " +
                                     s.time->to_string());
    // The series' step k as the prepared mesh: its points in the first
    // step's order where its triangles are the first step's, else its own
    // mesh (what a moving or changing mesh is at that step).
    const auto adopt = [&](std::size_t k, TriMesh step) {
      const std::string where = mesh_label + ": step " + std::to_string(k);
      if (step.vertex_count() != loaded.file_vertices ||
          topology_hash(step) != loaded.file_topology) {
        LoadedMesh own = for_key("mesh", [&] { return load_mesh(std::move(step), where, 0); });
        mesh = std::move(own.mesh);
        loaded.vertex_order = std::move(own.vertex_order);
        loaded.file_vertices = own.file_vertices;
        loaded.file_topology = own.file_topology;
        return;
      }
      std::vector<glm::vec3> moved = loaded.vertex_order.empty()
                                         ? step.positions
                                         : remap_vertex_data(step.positions, loaded.vertex_order);
      if (moved != mesh.positions) {
        for_key("mesh", [&] { check_finite(moved, where); });
        mesh.positions = std::move(moved);
        compute_vertex_normals(mesh);
      }
      take_arrays(mesh, step, loaded.vertex_order);
    };
    if (series_first == series_last && series_first > 0)
      adopt(series_first, loaded.read_step(series_first));
    // A solver's fields that start later than the mesh (OpenFOAM writes
    // wallShearStress from the first iteration on, not at time 0): with no
    // time asked for, the series starts at the first step that has the array.
    const auto has = [](const TriMesh& m, const std::string& name) {
      return m.vector_arrays.count(name) > 0 || m.scalars.count(name) > 0;
    };
    if (!s.time && field_spec && field_spec->kind == FieldKind::File &&
        !field_spec->array.empty() && !has(mesh, field_spec->array)) {
      for (std::size_t k = 1; k < count; ++k) {
        TriMesh step = loaded.read_step(k);
        if (!has(step, field_spec->array)) continue;
        adopt(k, std::move(step));
        p.warnings.push_back(
            mesh_label + ": " +
            (k == 1 ? "step 0 has" : "steps 0.." + std::to_string(k - 1) + " have") + " no '" +
            field_spec->array + "'; starting at step " + std::to_string(k));
        series_first = k;
        break;
      }
    }
  }
  p.source_vertices = loaded.file_vertices;
  p.source_topology = loaded.file_topology;
  p.vertex_order = loaded.vertex_order;
  // The points as read: a later state whose points equal these stands still.
  c.still = std::make_shared<const std::vector<glm::vec3>>(mesh.positions);
  if (s.time && s.time->last > s.time->first && !series && !(field_spec && own_time(*field_spec)))
    throw SettingError("time",
                       "a range A:B needs a series (.pvd, OpenFOAM times, numbered files), or "
                       "field wind:... or sample:...");
}

}  // namespace ibfvs::prep
