// What a preparation's steps share with prepare_change and resized: a
// step's data on the prepared mesh, the steps' cache, the fit to an image.
#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>

#include "ibfvs/core/geometry/displacement.h"
#include "ibfvs/core/geometry/vertex_scalar.h"
#include "ibfvs/core/mesh/gpu_prep.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/support/limits.h"
#include "steps.h"

namespace ibfvs::prep {

// A step's arrays (in file vertex order) onto the mesh, reordered like it.
void take_arrays(TriMesh& mesh, const TriMesh& step, const std::vector<unsigned>& order) {
  const auto put = [&](const auto& values) {
    return order.empty() ? values : remap_vertex_data(values, order);
  };
  if (step.vectors.size() == step.vertex_count() && !step.vectors.empty())
    mesh.vectors = put(step.vectors);
  for (const auto& [name, values] : step.vector_arrays) mesh.vector_arrays[name] = put(values);
  for (const auto& [name, values] : step.scalars) mesh.scalars[name] = put(values);
  for (const auto& [name, c] : step.other_arrays) mesh.other_arrays[name] = c;
}

// Throws InputError naming `where` and the point where a point is not finite.
void check_finite(const std::vector<glm::vec3>& points, const std::string& where) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::vec3& r = points[i];
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z))
      throw InputError(where + ": point " + std::to_string(i) + " is not a finite number (" +
                       std::to_string(r.x) + ", " + std::to_string(r.y) + ", " +
                       std::to_string(r.z) + ")");
  }
}

namespace {

// A step's points, normals and arrays (in the caller's order) onto `on`,
// whose triangles are set, in the prepared mesh's order; the prepared
// mesh's own points and normals where they did not move and the triangles
// are its own. `moved`: the points differ from those read first.
void take_step(const StepContext& c, const TriMesh& given, bool arrays_only, bool own_triangles,
               TriMesh& on, bool& moved) {
  const auto put = [&](const auto& values) {
    return c.order.empty() ? values : remap_vertex_data(values, c.order);
  };
  on.positions = arrays_only ? *c.still : put(given.positions);
  moved = on.positions != *c.still;
  if (!moved && !own_triangles) {
    on.positions = c.mesh->positions;
    on.normals = c.mesh->normals;
  } else if (given.normals.size() == given.vertex_count()) {
    on.normals = put(given.normals);
  } else {
    compute_vertex_normals(on);
  }
  on.scalars = c.mesh->scalars;  // what a step does not carry (curvature, netCDF scalars)
  take_arrays(on, given, c.order);
}

}  // namespace

std::optional<TriMesh> on_prepared_points(const StepContext& c, const TriMesh& given,
                                          const std::string& where, bool arrays_only) {
  if (given.vertex_count() != c.source_vertices || given.triangles.empty()) return std::nullopt;
  // Point i stays point i: the prepared mesh's order, the step's triangles
  // renumbered to it.
  validate_mesh(given, where);
  TriMesh others;
  others.triangles = given.triangles;
  if (!c.order.empty())
    for (Triangle& t : others.triangles)
      for (std::uint32_t& i : t)
        if ((i = c.order[i]) == ~0u) return std::nullopt;  // a point step 0 left out
  if (!most_edges_shared(c.mesh->triangles, others.triangles)) return std::nullopt;
  bool moved = false;
  take_step(c, given, arrays_only, true, others, moved);
  return others;
}

// A step's surface as given (the caller's order: a series file, a host's
// data) on the prepared mesh: the same triangles take its order and
// triangles, with its points and arrays; other triangles on the same points
// keep their order (on_prepared_points); else a mesh of its own (checked,
// normals, GPU order). `arrays_only`: only its arrays count (a field_step
// file on the scene's mesh, the same vertices). `moved`: the points differ
// from the prepared mesh's; `same`: its triangles (`same_known`: the caller
// compared them already).
TriMesh mesh_on(const StepContext& c, TriMesh given, const std::string& where, bool arrays_only,
                bool& same, bool& moved, bool same_known) {
  if (!arrays_only) check_finite(given.positions, where);
  moved = false;
  same = arrays_only || same_known ||
         (given.vertex_count() == c.source_vertices && topology_hash(given) == c.source_topology);
  if (!same) {
    if (given.triangles.empty()) throw InputError(where + ": no triangles");
    if (std::optional<TriMesh> others = on_prepared_points(c, given, where, arrays_only)) {
      moved = others->positions != *c.still;
      return std::move(*others);
    }
    return load_mesh(std::move(given), where, 0, true).mesh;  // checked, normals, GPU order
  }
  TriMesh on;
  on.triangles = c.mesh->triangles;
  take_step(c, given, arrays_only, false, on, moved);
  return on;
}

// The field and scalars of a surface, as the scene evaluates them.
void evaluate_step(const StepContext& c, const TriMesh& on, StepData& d) {
  d.field = evaluate_field(on, c.spec, c.tangent);
  if (c.reverse)
    for (glm::vec3& v : d.field) v = -v;
  if (!c.color_by.empty()) d.color_scalar = vertex_scalar(on, d.field, c.color_by);
  if (!c.beta_by.empty()) d.beta_scalar = vertex_scalar(on, d.field, c.beta_by);
}

StepData step_on_mesh(const StepContext& c, TriMesh given, const std::string& where,
                      bool arrays_only) {
  bool same = true, moved = false;
  TriMesh on = mesh_on(c, std::move(given), where, arrays_only, same, moved);
  StepData d;
  evaluate_step(c, on, d);
  if (!same) {
    d.mesh = std::make_shared<const TriMesh>(std::move(on));
  } else if (moved) {
    d.positions = std::move(on.positions);
    d.normals = std::move(on.normals);
  }
  return d;
}

namespace {

std::size_t step_bytes(const StepData& d) {
  return (d.field.size() + d.positions.size() + d.normals.size()) * sizeof(glm::vec3) +
         (d.color_scalar.size() + d.beta_scalar.size()) * sizeof(float) +
         (d.mesh ? d.mesh->vertex_count() * 3 * sizeof(glm::vec3) +
                       d.mesh->triangle_count() * sizeof(Triangle)
                 : 0);
}

}  // namespace

// The steps, each read once while they fit in a share of the memory (the
// scan for dt and the colour range reads them all, the animation again).
std::function<StepData(std::size_t)> cached_steps(std::function<StepData(std::size_t)> read,
                                                  std::size_t count) {
  struct Cache {
    std::mutex mutex;
    std::vector<std::shared_ptr<const StepData>> steps;
    std::size_t bytes = 0, budget = 0;
  };
  auto cache = std::make_shared<Cache>();
  cache->steps.resize(count);
  const std::uint64_t memory = memory_limit();
  cache->budget = memory > 0 ? std::min<std::uint64_t>(memory / 8, 2ull << 30) : 512ull << 20;
  return [cache, read = std::move(read)](std::size_t k) {
    {
      const std::lock_guard lock(cache->mutex);
      if (k < cache->steps.size() && cache->steps[k]) return *cache->steps[k];
    }
    StepData d = read(k);
    const std::lock_guard lock(cache->mutex);
    const std::size_t bytes = step_bytes(d);
    if (k < cache->steps.size() && cache->bytes + bytes <= cache->budget) {
      cache->steps[k] = std::make_shared<const StepData>(d);
      cache->bytes += bytes;
    }
    return d;
  };
}

// The steps a run plays: its frames at frames_per_step each (with the step
// each last frame runs towards); all of them where the run's length is
// automatic.
std::size_t steps_played(const PreparedScene& p) {
  if (p.step_count < 2 || p.frames <= 0) return p.step_count;
  const auto per_step = static_cast<std::size_t>(std::max(p.scene.frames_per_step, 1));
  return std::min(p.step_count, static_cast<std::size_t>(p.frames - 1) / per_step + 2);
}

// The positions a step's surface has.
const std::vector<glm::vec3>& step_positions(const StepData& d, const TriMesh& mesh) {
  return d.mesh ? d.mesh->positions : !d.positions.empty() ? d.positions : mesh.positions;
}

bool own_time(const FieldSpec& spec) {
  return spec.kind == FieldKind::Wind || spec.kind == FieldKind::Sample;
}

bool wants_curvature(const std::string& name) {
  const std::string n = !name.empty() && name[0] == '-' ? name.substr(1) : name;
  return n == "kmin" || n == "kmax";
}

// Checks that need no file.
void check(const Scene& s) {
  if (s.image_normalize && s.dt > 0.0f)
    throw SettingError("image_normalize", "moves every point step pixels; it takes no dt");
  if (!s.elements.empty() && s.field && s.field->kind != FieldKind::Elements)
    throw SettingError("element",
                       "needs field elements (or no field), got field " + s.field->text());
  if (!s.field_steps.empty() && s.subdivide > 0)
    throw SettingError("field_step", "cannot be combined with subdivide");
  if (!s.field_steps.empty() && s.field && s.field->kind != FieldKind::File)
    throw SettingError("field_step",
                       "needs field file[:ARRAY] (or no field), got field " + s.field->text());
  if (s.frames == 0 && s.lock_at != Scene::kLockAuto)
    throw SettingError("frames", "0 (automatic) needs lock_at auto");
}

// The fastest vertex's pixels per unit of dt in the scene's camera, over
// the steps played (not only the first: a run from rest has no flow
// there; normalised in image space, dt only needs a step that has flow).
void fit_speed(PreparedScene& p) {
  const Scene& s = p.scene;
  const Camera camera(mesh_bounds(*p.mesh), p.camera,
                      static_cast<float>(p.width) / static_cast<float>(p.height));
  float speed =
      max_pixel_speed(p.mesh->positions, p.field, camera.view_projection(), p.width, p.height);
  for (std::size_t k = 1; k < steps_played(p) && p.step_data; ++k) {
    if (s.image_normalize && speed > 0.0f) break;
    const StepData d = p.step_data(k);
    speed = std::max(speed, max_pixel_speed(step_positions(d, *p.mesh), d.field,
                                            camera.view_projection(), p.width, p.height));
  }
  p.pixel_speed = speed;
}

void fit_dt(PreparedScene& p) {
  const Scene& s = p.scene;
  p.dt = scene_dt(s, p.pixel_speed);
  p.max_px = s.image_normalize && p.pixel_speed > 0.0f ? s.step : p.pixel_speed * p.dt;
}

// Sets the image size and what follows from it with the scene's camera: dt
// from the step in pixels (unless the scene gives dt), the fastest vertex's
// pixels per frame, the object-noise cell (s pixels at the mesh centre).
// Returns the fastest vertex's pixels per unit of dt (0: nothing moves).
float fit_to_image(PreparedScene& p, int width, int height) {
  p.width = p.settings.width = width;
  p.height = p.settings.height = height;
  fit_speed(p);
  fit_dt(p);
  if (p.settings.object_noise) {
    const Camera camera(mesh_bounds(*p.mesh), p.camera,
                        static_cast<float>(width) / static_cast<float>(height));
    p.settings.object_cell = p.settings.noise.scale * camera.world_per_pixel(height);
  }
  return p.pixel_speed;
}

}  // namespace ibfvs::prep
