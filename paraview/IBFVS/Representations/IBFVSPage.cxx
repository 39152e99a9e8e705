// A page of ParaView's view: its IBFVS surfaces over the data's times as one
// scene (vtkIBFVSPageExporter writes it).
#include "IBFVSPage.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs::paraview {
namespace {

// Why two layers cannot share a page's one look (empty: they can).
std::string differs(const PageLayer& a, const PageLayer& b) {
  for (const std::string_view key : ibfvs::changed_keys(a.scene, b.scene))
    if (key != "color_by" && key != "color_range") return "its " + std::string(key);
  if (a.table.empty() != b.table.empty()) return "one is coloured by an array, the other is not";
  if (a.table != b.table) return "their colour maps or ranges";
  if (a.table.empty() && a.scene.surface_color != b.scene.surface_color) return "its colour";
  return {};
}

// Appends `layer`'s surface to `into` (normals computed where it has none,
// so that every layer keeps its own).
void append(ibfvs::TriMesh& into, PageLayer& layer) {
  ibfvs::TriMesh& m = layer.mesh;
  if (m.normals.size() != m.positions.size()) ibfvs::compute_vertex_normals(m);
  ibfvs::append_mesh(into, m);
  m = ibfvs::TriMesh{};
}

}  // namespace

ibfvs::PreparedScene page_scene(std::vector<std::vector<PageLayer>> steps, const PageView& view,
                                const std::string& name) {
  const PageLayer* look = nullptr;
  for (const auto& layers : steps)
    for (const PageLayer& layer : layers) {
      if (!look) {
        look = &layer;
      } else if (const std::string why = differs(*look, layer); !why.empty()) {
        throw ibfvs::InputError("the visible IBFVS representations differ in " + why + " (" +
                                look->name + ", " + layer.name +
                                "); a page has one look: hide one, or give them the same settings");
      }
    }
  if (!look) throw ibfvs::InputError("no IBFVS representation is visible in the view");

  ibfvs::Scene scene = look->scene;
  const std::vector<glm::vec3> table = look->table;
  const bool coloured = !table.empty();
  scene.width = view.width;
  scene.height = view.height;
  scene.field = ibfvs::FieldSpec::parse("file");
  scene.lock_at = ibfvs::Scene::kLockNever;
  scene.orbit = 0.0f;
  scene.subdivide = 0;
  scene.color_by = coloured ? kTableColour : "";
  scene.color_range.reset();
  if (coloured) scene.color_range = ibfvs::ScalarRange{false, 0.0f, 1.0f};
  // Every time played: its frames at Frames Per Step each.
  scene.frames = static_cast<int>(steps.size()) * std::max(scene.frames_per_step, 1) + 1;

  // ---- each time's layers as one surface
  std::vector<ibfvs::TriMesh> states;
  float speed = 0.0f;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    ibfvs::TriMesh merged;
    for (PageLayer& layer : steps[k]) {
      speed = std::max(speed, layer.speed);
      append(merged, layer);
    }
    if (merged.triangles.empty())
      throw ibfvs::InputError("no IBFVS surface at time step " + std::to_string(k) +
                              " (hidden, or empty there)");
    states.push_back(std::move(merged));
  }
  // Times at which nothing shown changed (another source's times, in the
  // time keeper's union) are one step: the page holds the surface once.
  const auto same = [&](const ibfvs::TriMesh& m) {
    const ibfvs::TriMesh& first = states.front();
    return m.positions == first.positions && m.triangles == first.triangles &&
           m.vectors == first.vectors && m.scalars == first.scalars;
  };
  if (std::all_of(states.begin() + 1, states.end(), same)) states.resize(1);
  // dt as the mapper's (the one rule, scene_dt): the fastest vector of all
  // times moves Step pixels at the focal point. Normalised in image space
  // the scene takes no dt key (every point moves Step pixels whatever dt
  // is): the page fits one from the step.
  if (!scene.image_normalize)
    scene.dt = ibfvs::scene_dt(
        scene, speed,
        ibfvs::world_per_pixel(view.camera.projection, view.focal_distance, view.height));

  ibfvs::PreparedScene p = ibfvs::prepare_states(scene, std::move(states), name);
  p.settings.color_table = table;
  // ParaView's camera: its matrices, turning about its focal point.
  p.camera.host = view.camera;
  p.camera.target = view.focal - ibfvs::mesh_bounds(*p.mesh).centre();
  return ibfvs::resized(p, view.width, view.height);
}

}  // namespace ibfvs::paraview
