#include "ibfvs/core/scene/scene_prep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <set>
#include <string_view>

#include <glm/trigonometric.hpp>

#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/geometry/curvature.h"
#include "ibfvs/core/geometry/displacement.h"
#include "ibfvs/core/image/colormap.h"
#include "ibfvs/core/mesh/gpu_prep.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/scene/mesh_source.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/limits.h"
#include "ibfvs/core/support/text.h"
#include "prepare/steps.h"

namespace ibfvs {
namespace fs = std::filesystem;

using namespace prep;

void fit_to_size(PreparedScene& prepared, int width, int height) {
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
    throw SettingError("size", "width and height must be between 1 and " +
                                   std::to_string(kMaxImageSide) + " pixels");
  fit_to_image(prepared, width, height);
}

void fit_field(PreparedScene& prepared) {
  fit_speed(prepared);
  fit_dt(prepared);
}

PreparedScene resized(const PreparedScene& prepared, int width, int height) {
  PreparedScene p = prepared;
  fit_to_size(p, width, height);
  return p;
}

TriMesh step_surface(const PreparedScene& prepared, const StepData& step) {
  TriMesh mesh = step.mesh ? *step.mesh : *prepared.mesh;
  if (!step.mesh && !step.positions.empty()) mesh.positions = step.positions;
  return mesh;
}

ChangePlan apply_change(PreparedScene& p, const Scene& next, float world_per_pixel) {
  const ChangePlan plan = plan_change(p.scene, next, p.step_count > 1);
  if (!plan.takes()) return plan;

  // Everything checked before anything changes: the settings at the new size.
  RenderSettings settings = p.settings;
  settings.width = next.width;
  settings.height = next.height;
  settings = scene_settings(next, settings);
  settings.width = p.settings.width;
  settings.height = p.settings.height;
  if (settings.object_noise && (!p.settings.object_noise || plan.regrid)) {
    // s pixels at the distance of the mesh centre, as prepare_scene does.
    settings.object_cell = settings.noise.scale * world_per_pixel;
  }
  std::vector<glm::vec3> field;
  if (plan.tangent) field = evaluate_field(*p.mesh, p.field_spec, next.tangent);

  p.scene = next;
  p.settings = settings;
  if (plan.tangent) p.field = std::move(field);
  if (plan.camera) {
    const glm::vec3 up = p.camera.up;  // the prepared scene's up (a key of its own)
    p.camera = next.camera;
    p.camera.up = up;
  }
  if (plan.camera || plan.size)
    fit_to_image(p, next.width, next.height);  // dt, and the object cell for the view
  else if (plan.tangent)
    fit_speed(p);
  if (plan.step || plan.tangent) fit_dt(p);
  return plan;
}

std::optional<PreparedScene> restyled(const PreparedScene& prepared, Style style) {
  Scene s = prepared.scene;
  apply_style(s, style);
  // The keys a restyle carries: texture settings, the noise grid and the
  // step (dt follows), over the same field, camera and size.
  if (changed_keys(prepared.scene, s).empty()) return prepared;
  PreparedScene p = prepared;
  const Camera camera(mesh_bounds(*p.mesh), p.camera,
                      static_cast<float>(p.width) / static_cast<float>(p.height));
  const ChangePlan plan = apply_change(p, s, camera.world_per_pixel(p.height));
  if (plan.prepare || plan.tangent || plan.camera || plan.size) return std::nullopt;
  return p;
}

RenderSettings scene_settings(const Scene& s, RenderSettings settings) {
  settings.alpha = s.alpha;
  settings.beta = s.beta;
  settings.image_step = s.image_normalize ? s.step : 0.0f;
  settings.filter_length = s.filter;
  settings.resample = s.resample;
  settings.sharpen = s.sharpen;
  settings.contrast = s.contrast;
  settings.noise.profile = s.profile;
  settings.noise.rate = s.vg;
  settings.noise.spike_width = s.spike_width;
  settings.noise.scale = s.scale;
  settings.noise.seed = s.seed;
  settings.inject = s.inject;
  settings.background = s.background;
  settings.surface_color = s.surface_color;
  settings.advect_view = s.advect_view;
  settings.field_frame = s.field_frame;
  settings.object_noise = s.noise_space == NoiseSpace::Object;
  settings.color_map = s.color_map;
  if (s.color_range && !s.color_range->percentile)
    settings.color_range = {s.color_range->lo, s.color_range->hi};
  if (s.beta_range && !s.beta_range->percentile)
    settings.beta_range = {s.beta_range->lo, s.beta_range->hi};
  settings.validate();
  return settings;
}

float scene_dt(const Scene& s, float pixel_speed) {
  return s.dt > 0.0f ? s.dt : dt_for_step(s.step, pixel_speed);
}

float scene_dt(const Scene& s, float world_speed, double world_per_pixel) {
  return s.dt > 0.0f ? s.dt : dt_for_step(s.step, world_speed, world_per_pixel);
}

glm::vec3 thinnest_axis(const TriMesh& mesh) {
  const Bounds b = mesh_bounds(mesh);
  const glm::vec3 e = b.max - b.min;
  const int axis = e.x <= e.y && e.x <= e.z ? 0 : e.y <= e.z ? 1 : 2;
  glm::vec3 up(0.0f);
  up[axis] = 1.0f;
  return up;
}

namespace {

// The preparation, a chain of steps over one context (prepare/steps.h).
PreparedScene prepare(const Scene& s, std::optional<LoadedMesh> given) {
  check(s);
  Preparation c(s, std::move(given));
  for (void (*step)(Preparation&) :
       {settings, load, series, orient, surface_scalars, field, pace, colours})
    step(c);
  c.p.mesh = std::move(c.mesh);
  c.p.field_spec = *c.field_spec;
  return std::move(c.p);
}

}  // namespace

std::string field_text(const PreparedScene& p) {
  std::string out = p.field_spec.to_string();
  const std::vector<std::string>& when = p.step_labels;
  if (when.size() == 1) {
    out += " (" + when.front() + ")";
  } else if (when.size() > 1) {
    const std::size_t first = p.scene.time ? p.scene.time->first : 0;
    out += " to " + std::to_string(first + when.size() - 1) + " (" + when.front() + " to " +
           when.back() + ")";
  }
  return out;
}

PreparedScene prepare_scene(const Scene& scene) {
  return prepare(scene, std::nullopt);
}

PreparedScene prepare_scene(const Scene& scene, TriMesh mesh, const std::string& name) {
  return prepare(scene, for_key("mesh", [&] {
                   return load_mesh(std::move(mesh), name, scene.subdivide, true);
                 }));
}

}  // namespace ibfvs

namespace ibfvs {

PreparedScene prepare_change(const PreparedScene& prepared, TriMesh mesh, const std::string& name) {
  const Scene& s = prepared.scene;
  // Subdivided or displaced, the prepared mesh is not the given one moved.
  // Other triangles on the same points stay on the prepared mesh's points
  // (mesh_on); other points are another scene.
  if (s.subdivide > 0 || s.displace || !prepared.mesh ||
      mesh.vertex_count() != prepared.source_vertices)
    return prepare_scene(s, std::move(mesh), name);
  const std::uint64_t topology = topology_hash(mesh);
  StepContext c;
  c.mesh = prepared.mesh;
  c.still = std::shared_ptr<const std::vector<glm::vec3>>(prepared.mesh, &prepared.mesh->positions);
  c.order = prepared.vertex_order;
  c.source_vertices = prepared.source_vertices;
  c.source_topology = prepared.source_topology;
  c.spec = prepared.field_spec;
  c.tangent = s.tangent;
  c.reverse = s.reverse;
  if (prepared.settings.use_color) c.color_by = s.color_by;
  if (prepared.settings.use_beta) c.beta_by = s.beta_by;
  TriMesh on;
  if (topology == prepared.source_topology) {
    bool same = true, moved = false;
    on = mesh_on(c, std::move(mesh), name, false, same, moved, true);  // hashed above
  } else if (std::optional<TriMesh> others = on_prepared_points(c, mesh, name)) {
    on = std::move(*others);  // checked there (validate_mesh)
  } else {
    return prepare_scene(s, std::move(mesh), name);
  }
  StepData d;
  evaluate_step(c, on, d);
  PreparedScene next = prepared;
  next.step_count = 1;
  next.step_data = nullptr;
  next.step_labels.clear();
  next.field = std::move(d.field);
  next.color_scalar = std::move(d.color_scalar);
  next.beta_scalar = std::move(d.beta_scalar);
  next.mesh = std::make_shared<const TriMesh>(std::move(on));
  next.source_topology = topology;  // the next change compares with these triangles
  return next;
}

}  // namespace ibfvs
