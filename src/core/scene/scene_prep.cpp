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

namespace ibfvs {
namespace fs = std::filesystem;

namespace {

// Runs `f`, turning a plain InputError into a SettingError of `key`.
template <class F>
auto for_key(const char* key, F&& f) {
  try {
    return f();
  } catch (const SettingError&) {
    throw;
  } catch (const InputError& e) {
    throw SettingError(key, e.what());
  }
}

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

// What a step's surface is put on the prepared mesh with.
struct StepContext {
  std::shared_ptr<const TriMesh> mesh;  // the prepared mesh (the first step's)
  // Its points as read, in its order, before any displacement: a step whose
  // points equal these stands still.
  std::shared_ptr<const std::vector<glm::vec3>> still;
  std::vector<unsigned> order;  // new index of each vertex as given
  std::size_t source_vertices = 0;
  std::uint64_t source_topology = 0;
  FieldSpec spec;
  TangentMode tangent = TangentMode::Project;
  bool reverse = false;
  std::string color_by, beta_by;
};

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

// A step's surface as given (the caller's order: a series file, a host's
// data) on the prepared mesh: the same triangles take its order and
// triangles, with its points and arrays; other triangles are a mesh of
// their own (checked, normals, GPU order). `arrays_only`: only its arrays
// count (a field_step file on the scene's mesh, the same vertices).
// `moved`: the points differ from the prepared mesh's; `same`: its triangles
// (`same_known`: the caller compared them already).
TriMesh mesh_on(const StepContext& c, TriMesh given, const std::string& where, bool arrays_only,
                bool& same, bool& moved, bool same_known = false) {
  if (!arrays_only) check_finite(given.positions, where);
  const auto put = [&](const auto& values) {
    return c.order.empty() ? values : remap_vertex_data(values, c.order);
  };
  moved = false;
  same = arrays_only || same_known ||
         (given.vertex_count() == c.source_vertices && topology_hash(given) == c.source_topology);
  if (!same) {
    if (given.triangles.empty()) throw InputError(where + ": no triangles");
    return load_mesh(std::move(given), where, 0, true).mesh;  // checked, normals, GPU order
  }
  TriMesh on;
  on.positions = arrays_only ? *c.still : put(given.positions);
  on.triangles = c.mesh->triangles;
  if (on.positions == *c.still) {
    on.positions = c.mesh->positions;
    on.normals = c.mesh->normals;
  } else {
    moved = true;
    if (given.normals.size() == given.vertex_count())
      on.normals = put(given.normals);
    else
      compute_vertex_normals(on);
  }
  on.scalars = c.mesh->scalars;  // what a step does not carry (curvature, netCDF scalars)
  take_arrays(on, given, c.order);
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
                      bool arrays_only = false) {
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

std::size_t step_bytes(const StepData& d) {
  return (d.field.size() + d.positions.size() + d.normals.size()) * sizeof(glm::vec3) +
         (d.color_scalar.size() + d.beta_scalar.size()) * sizeof(float) +
         (d.mesh ? d.mesh->vertex_count() * 3 * sizeof(glm::vec3) +
                       d.mesh->triangle_count() * sizeof(Triangle)
                 : 0);
}

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

// Sets the image size and what follows from it with the scene's camera: dt
// from the step in pixels (unless the scene gives dt), the fastest vertex's
// pixels per frame, the object-noise cell (s pixels at the mesh centre).
// Returns the fastest vertex's pixels per unit of dt (0: nothing moves).
float fit_to_image(PreparedScene& p, int width, int height) {
  const Scene& s = p.scene;
  p.width = p.settings.width = width;
  p.height = p.settings.height = height;
  const Camera camera(mesh_bounds(*p.mesh), p.camera,
                      static_cast<float>(width) / static_cast<float>(height));
  // The fastest vertex of the steps played, not only of the first (a run
  // from rest has no flow there); normalised in image space, dt only needs
  // a step that has flow.
  float speed =
      max_pixel_speed(p.mesh->positions, p.field, camera.view_projection(), width, height);
  for (std::size_t k = 1; k < steps_played(p) && p.step_data; ++k) {
    if (s.image_normalize && speed > 0.0f) break;
    const StepData d = p.step_data(k);
    speed = std::max(speed, max_pixel_speed(step_positions(d, *p.mesh), d.field,
                                            camera.view_projection(), width, height));
  }
  p.dt = s.dt > 0.0f ? s.dt : dt_for_step(s.step, speed);
  p.max_px = s.image_normalize && speed > 0.0f ? s.step : speed * p.dt;
  if (p.settings.object_noise) {
    p.settings.object_cell = p.settings.noise.scale * camera.world_per_pixel(height);
  }
  return speed;
}

}  // namespace

PreparedScene resized(const PreparedScene& prepared, int width, int height) {
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
    throw SettingError("size", "width and height must be between 1 and " +
                                   std::to_string(kMaxImageSide) + " pixels");
  PreparedScene p = prepared;
  fit_to_image(p, width, height);
  return p;
}

std::optional<PreparedScene> restyled(const PreparedScene& prepared, Style style) {
  Scene s = prepared.scene;
  apply_style(s, style);
  // The keys a restyle carries (plan_change): texture settings, the noise
  // grid and the step (dt is computed again below), over the same field,
  // camera and size.
  const ChangePlan plan = plan_change(prepared.scene, s, prepared.step_count > 1);
  if (plan.prepare || plan.tangent || plan.camera || plan.size) return std::nullopt;
  PreparedScene p = prepared;
  p.scene = s;
  apply_texture_settings(s, p.settings);
  p.settings.noise.scale = s.scale;
  p.settings.noise.seed = s.seed;
  p.settings.validate();
  fit_to_image(p, p.width, p.height);
  return p;
}

void apply_texture_settings(const Scene& s, RenderSettings& settings) {
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

PreparedScene prepare(const Scene& s, std::optional<LoadedMesh> given) {
  check(s);
  PreparedScene p;
  p.scene = s;
  p.width = s.width;
  p.height = s.height;
  p.frames = s.frames;
  p.lock_at = s.lock_at;

  RenderSettings& settings = p.settings;
  settings.width = s.width;
  settings.height = s.height;
  apply_texture_settings(s, settings);
  settings.noise.scale = s.scale;
  settings.noise.seed = s.seed;
  settings.validate();

  std::optional<FieldSpec> field_spec = s.field;
  if (!field_spec && !s.elements.empty()) field_spec = FieldSpec::parse("elements");
  const std::size_t time_first = s.time ? s.time->first : 0;
  if (field_spec) {
    for (const FlowElement& e : s.elements) field_spec->elements.push_back(e);
    field_spec->time = time_first;
  }

  // ---- mesh
  const bool in_memory = given.has_value();
  LoadedMesh loaded =
      in_memory ? std::move(*given)
                : for_key("mesh", [&] { return load_mesh(s.mesh, s.subdivide, true, s.blocks); });
  for (const std::string& w : loaded.warnings) p.warnings.push_back(w);
  auto mesh_ptr = std::make_shared<TriMesh>(std::move(loaded.mesh));
  TriMesh& mesh = *mesh_ptr;
  p.demo = loaded.demo;
  p.mesh_name = loaded.demo || in_memory ? loaded.name : fs::path(s.mesh).filename().string();
  // Messages about the mesh's data name the file as given.
  const std::string mesh_label = loaded.demo || in_memory ? p.mesh_name : s.mesh;

  // ---- a series: its steps (all, or the time key's range or step)
  const bool series = !loaded.step_times.empty();
  std::size_t series_first = 0, series_last = 0;
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
  const auto still = std::make_shared<const std::vector<glm::vec3>>(mesh.positions);
  const bool field_is_file =
      (field_spec && field_spec->kind == FieldKind::File) ||
      (!field_spec && (!mesh.vector_arrays.empty() || mesh.vectors.size() == mesh.vertex_count()));
  if (s.time && s.time->last > s.time->first && !(series && field_is_file) &&
      !(field_spec &&
        (field_spec->kind == FieldKind::Wind || field_spec->kind == FieldKind::Sample)))
    throw SettingError("time",
                       "a range A:B needs a series (.pvd, OpenFOAM times, numbered files) with "
                       "field file[:ARRAY], or field wind:... or sample:...");

  // ---- the height axis
  const glm::vec3 up = s.up_auto ? thinnest_axis(mesh) : s.up.value_or(glm::vec3(0, 1, 0));
  p.camera = s.camera;
  p.camera.up = up;
  // A flat surface (one wall patch, a plate) seen edge-on from the default
  // view shows nothing: the default view then looks at its face.
  if (!s.up_auto && !s.up && s.camera.azimuth_deg == 0.0f && s.camera.elevation_deg == 0.0f &&
      s.camera.target == glm::vec3(0.0f)) {
    const Bounds b = mesh_bounds(mesh);
    const glm::vec3 e = b.max - b.min;
    const float largest = std::max({e.x, e.y, e.z});
    if (e.x <= 1e-4f * largest)
      p.camera.azimuth_deg = 90.0f;  // from +X
    else if (e.y <= 1e-4f * largest)
      p.camera.elevation_deg = 90.0f;  // from +Y, down
  }
  if (field_spec && field_spec->kind == FieldKind::Gradient && !field_spec->vector_given)
    field_spec->value = up;
  std::optional<FieldSpec> default_field = s.default_field;
  if (default_field && default_field->kind == FieldKind::Gradient && !default_field->vector_given)
    default_field->value = up;
  if (s.lock_camera)
    p.lock_camera = CameraParams{s.lock_camera->x,
                                 s.lock_camera->y,
                                 s.lock_camera->z,
                                 s.camera.orthographic,
                                 s.camera.fov_deg,
                                 glm::vec3(0.0f),
                                 up,
                                 std::nullopt};

  // ---- scalars sampled from netCDF grids
  for (const GridScalar& g : s.scalars) {
    LonLatGrid grid = read_lonlat_grid(g.path, g.variable, 0);
    if (grid.time_steps > 1) grid = read_lonlat_grid(g.path, g.variable, time_first);
    mesh.scalars[g.name] = lonlat_scalars(mesh, grid);
  }

  // ---- curvature, once, when the field or a scalar needs it
  {
    const bool principal =
        (field_spec && field_spec->kind == FieldKind::Principal) ||
        (!field_spec && default_field && default_field->kind == FieldKind::Principal);
    if ((principal || wants_curvature(s.color_by) || wants_curvature(s.beta_by) ||
         (s.displace && wants_curvature(s.displace->scalar))) &&
        !mesh.scalars.count("kmax"))
      store_curvature(mesh, compute_curvature(mesh), false);
  }

  // ---- displacement along the normals (the vertical scale of a relief)
  if (s.displace) {
    if (!std::isfinite(s.displace->factor))
      throw SettingError("displace", "the factor must be a finite number");
    std::vector<float> amount;
    try {
      amount = vertex_scalar(mesh, {}, s.displace->scalar);
    } catch (const InputError& e) {
      throw SettingError("displace", mesh_label + ": " + e.what());
    }
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
      if (std::isfinite(amount[i]))
        mesh.positions[i] += s.displace->factor * amount[i] * mesh.normals[i];
    compute_vertex_normals(mesh);
  }

  // ---- field
  if (!field_spec) {
    field_spec = mesh.vectors.size() == mesh.positions.size() || !mesh.vector_arrays.empty()
                     ? FieldSpec::parse("file")
                 : default_field                              ? *default_field
                 : loaded.generated_landscape ? [&] {
                     FieldSpec g = FieldSpec::parse("gradient:down");
                     g.value = up;
                     return g;
                   }()
                                              : FieldSpec::parse("rotate:0,1,0");
  }
  const TangentMode tangent = s.tangent;
  // The data at a step on this mesh: a series' surfaces (points that move,
  // triangles that change), another file's arrays, a field at another time.
  StepContext context;
  context.mesh = mesh_ptr;
  context.still = still;
  context.order = loaded.vertex_order;
  context.source_vertices = loaded.file_vertices;
  context.source_topology = loaded.file_topology;
  context.spec = *field_spec;
  context.tangent = tangent;
  context.reverse = s.reverse;
  context.color_by = s.color_by;
  context.beta_by = s.beta_by;
  if (!s.field_steps.empty()) {
    // An unsteady field: its steps, evaluated when the animation reaches them.
    p.step_count = s.field_steps.size();
    p.step_data = [files = s.field_steps, expected = loaded.file_vertices, blocks = s.blocks,
                   context](std::size_t k) {
      const std::string& file = files[k];
      TriMesh step = read_any_mesh(file, blocks);
      if (step.vertex_count() != expected)
        throw SettingError("field_step", file + ": " + std::to_string(step.vertex_count()) +
                                             " vertices, the mesh has " + std::to_string(expected));
      try {
        return step_on_mesh(context, std::move(step), file, true);
      } catch (const InputError& e) {
        throw SettingError("field_step", e.what());
      }
    };
  } else if (series && field_spec->kind == FieldKind::File && series_last > series_first) {
    p.step_count = series_last - series_first + 1;
    p.step_data = [read = loaded.read_step, first = series_first, context,
                   label = mesh_label](std::size_t k) {
      const std::string where = label + ": step " + std::to_string(first + k);
      try {
        return step_on_mesh(context, read(first + k), where);
      } catch (const SettingError&) {
        throw;
      } catch (const InputError& e) {
        const std::string what = e.what();
        throw SettingError("field", what.rfind(where, 0) == 0 ? what : where + ": " + what);
      }
    };
  } else if (s.time && s.time->last > s.time->first) {
    p.step_count = s.time->last - s.time->first + 1;
    if (field_spec->kind == FieldKind::Wind)
      read_lonlat_grid(field_spec->path, field_spec->east, s.time->last);  // the range exists
    p.step_data = [context, first = s.time->first](std::size_t k) {
      StepData d;
      FieldSpec at = context.spec;
      at.time = first + k;
      d.field = evaluate_field(*context.mesh, at, context.tangent);
      if (context.reverse)
        for (glm::vec3& v : d.field) v = -v;
      if (!context.color_by.empty())
        d.color_scalar = vertex_scalar(*context.mesh, d.field, context.color_by);
      if (!context.beta_by.empty())
        d.beta_scalar = vertex_scalar(*context.mesh, d.field, context.beta_by);
      return d;
    };
  }
  if (p.step_data) p.step_data = cached_steps(std::move(p.step_data), p.step_count);
  FieldReport field_report;
  try {
    if (p.step_data) {
      p.field = p.step_data(0).field;
    } else {
      p.field = evaluate_field(mesh, *field_spec, tangent, &field_report);
      if (s.reverse)
        for (glm::vec3& x : p.field) x = -x;
    }
  } catch (const SettingError&) {
    throw;
  } catch (const InputError& e) {
    throw SettingError("field", mesh_label + ": " + e.what());
  }
  if (field_report.outside_volume > 0)
    p.warnings.push_back(field_spec->path + ": " + std::to_string(field_report.outside_volume) +
                         " of " + std::to_string(mesh.vertex_count()) +
                         " vertices lie outside the volume (their vectors are zero)");
  if (field_report.non_finite_zeroed > 0)
    p.warnings.push_back(mesh_label + ": " + std::to_string(field_report.non_finite_zeroed) +
                         " vectors were NaN or infinite and are set to zero");

  // ---- camera and dt
  p.mesh = mesh_ptr;
  const float speed = fit_to_image(p, s.width, s.height);
  const Camera camera(mesh_bounds(mesh), p.camera,
                      static_cast<float>(s.width) / static_cast<float>(s.height));
  if (speed == 0.0f)
    p.warnings.push_back(
        "the field does not move any vertex in the image (zero after projection?); the texture "
        "will stand still");
  char text[200];
  // The display filter bridges gaps up to its length.
  if (p.max_px > settings.noise.scale && p.max_px > settings.filter_length) {
    std::snprintf(text, sizeof text,
                  "the largest displacement is %.1f pixels per frame, more than the noise scale "
                  "%.1f and the filter length %.1f: expect broken streaks (lower step or dt, or "
                  "raise filter)",
                  p.max_px, settings.noise.scale, settings.filter_length);
    p.warnings.push_back(text);
  }

  // ---- the automatic lock: once the texture has had time to cross the mesh
  // as seen (the colours of figure 7 travel from the summits to the basin
  // borders at max_px pixels per frame at most; a path is at most the
  // diagonal of the mesh's image), plus a fifth for slower slopes.
  if (s.lock_at == Scene::kLockAuto) {
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& r : mesh.positions) {
      const glm::vec2 px = project_to_pixels(camera.view_projection(), r, s.width, s.height);
      lo = glm::min(lo, px);
      hi = glm::max(hi, px);
    }
    lo = glm::max(lo, glm::vec2(0.0f));
    hi = glm::min(hi, glm::vec2(static_cast<float>(s.width), static_cast<float>(s.height)));
    const float extent = glm::length(glm::max(hi - lo, glm::vec2(0.0f)));
    p.lock_at = p.max_px > 0.0f ? static_cast<int>(std::ceil(1.2f * extent / p.max_px)) : 0;
    p.lock_at = std::clamp(p.lock_at, 1, 100000);
    if (s.frames == 0) p.frames = p.lock_at + 60;
  }

  // ---- scalars for colour and beta, and their ranges
  const auto scalar_range = [&](const std::string& name, const char* key,
                                const std::optional<ScalarRange>& range, const char* range_key,
                                std::vector<float>& values, bool colour) {
    try {
      values = vertex_scalar(mesh, p.field, name);
    } catch (const InputError& e) {
      throw SettingError(key, mesh_label + ": " + e.what());
    }
    // Percentiles of the steps played (a run from rest has none at the first).
    std::vector<float> all;
    if (p.step_data && p.step_count > 1 && (!range || range->percentile)) {
      all = values;
      for (std::size_t k = 1; k < steps_played(p); ++k) {
        const StepData d = p.step_data(k);
        const std::vector<float>& v = colour ? d.color_scalar : d.beta_scalar;
        all.insert(all.end(), v.begin(), v.end());
      }
    }
    const std::vector<float>& sample = all.empty() ? values : all;
    if (!range) return quantile_range(sample);
    if (range->percentile) return quantile_range(sample, range->lo / 100.0f, range->hi / 100.0f);
    if (!(range->hi > range->lo)) throw SettingError(range_key, "expected LO < HI");
    return glm::vec2(range->lo, range->hi);
  };
  if (!s.color_by.empty()) {
    settings.use_color = true;
    settings.color_range =
        scalar_range(s.color_by, "color_by", s.color_range, "color_range", p.color_scalar, true);
  }
  if (!s.beta_by.empty()) {
    settings.use_beta = true;
    settings.beta_range =
        scalar_range(s.beta_by, "beta_by", s.beta_range, "beta_range", p.beta_scalar, false);
  }
  settings.validate();

  // ---- the surface image, read once
  if (!s.surface_image.empty())
    p.surface_image = for_key("surface_image", [&] { return read_png(s.surface_image); });

  p.mesh = std::move(mesh_ptr);
  p.field_spec = *field_spec;
  return p;
}

}  // namespace

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
  if (s.subdivide > 0 || s.displace || !prepared.mesh ||
      mesh.vertex_count() != prepared.source_vertices ||
      topology_hash(mesh) != prepared.source_topology)
    return prepare_scene(s, std::move(mesh), name);
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
  bool same = true, moved = false;
  TriMesh on = mesh_on(c, std::move(mesh), name, false, same, moved, true);  // hashed above
  StepData d;
  evaluate_step(c, on, d);
  PreparedScene next = prepared;
  next.step_count = 1;
  next.step_data = nullptr;
  next.field = std::move(d.field);
  next.color_scalar = std::move(d.color_scalar);
  next.beta_scalar = std::move(d.beta_scalar);
  next.mesh = std::make_shared<const TriMesh>(std::move(on));
  return next;
}

}  // namespace ibfvs
