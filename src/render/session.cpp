#include "ibfvs/render/session.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/geometry/displacement.h"
#include "ibfvs/core/geometry/rigid_motion.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/objects.h"

namespace ibfvs {

namespace {

// The positions and normals a step's surface has.
const std::vector<glm::vec3>& positions_of(const StepData& d, const TriMesh& mesh) {
  return d.positions.empty() ? mesh.positions : d.positions;
}
const std::vector<glm::vec3>& normals_of(const StepData& d, const TriMesh& mesh) {
  return d.normals.empty() ? mesh.normals : d.normals;
}

void set_scene_scalars(const PreparedScene& scene, IbfvsRenderer& renderer,
                       const std::vector<float>& colour, const std::vector<float>& beta) {
  if (scene.settings.use_color || scene.settings.use_beta) renderer.set_scalars(colour, beta);
}

}  // namespace

// Plays an unsteady scene: the current and next steps on the GPU and the mix
// between them; the surface too where it moves (the same triangles: points
// interpolated like the field) or changes (a step with triangles of its own
// replaces the mesh, keeping the texture). Does nothing for a steady scene.
class Session::StepPlayer {
 public:
  StepPlayer(const PreparedScene& scene, IbfvsRenderer& renderer) : scene_(scene) {
    if (scene.step_count < 2) return;
    current_ = scene.step_data(0);
    next_ = scene.step_data(1);
    next_step_ = 1;
    on_renderer_ = scene.mesh.get();
    apply(renderer);
  }

  // Time t in steps as played (Session::seek took it through
  // session_time); evaluates a step only when t leaves the current one.
  void seek(double t, IbfvsRenderer& renderer) {
    const std::size_t n = scene_.step_count;
    if (n < 2) return;
    const auto s = std::min(static_cast<std::size_t>(t), n - 1);
    const std::size_t after = following(s);
    if (s != step_ || after != next_step_) {
      // Playing on, the next step is already at hand; a jump evaluates both.
      if (s != step_) current_ = s == next_step_ ? std::move(next_) : scene_.step_data(s);
      next_ = scene_.step_data(after);
      step_ = s;
      next_step_ = after;
      apply(renderer);
    }
    mix_ = static_cast<float>(t - static_cast<double>(s));
    renderer.set_field_mix(mix_);
  }

  [[nodiscard]] std::size_t step() const { return step_; }
  // The step played into: the next one where the two are interpolated
  // (their points correspond), else the step itself (it holds).
  [[nodiscard]] std::size_t next_step() const { return pair_ ? next_step_ : step_; }
  // The fraction of the step played (the field's mix).
  [[nodiscard]] float mix() const { return mix_; }
  // The step shown: its surface (moved where it moves) and field.
  [[nodiscard]] TriMesh surface() const { return step_surface(scene_, current_); }
  [[nodiscard]] const std::vector<glm::vec3>& field() const { return current_.field; }
  // The step played into (next_step): its surface and field.
  [[nodiscard]] TriMesh next_surface() const {
    return step_surface(scene_, pair_ ? next_ : current_);
  }
  [[nodiscard]] const std::vector<glm::vec3>& next_field() const {
    return (pair_ ? next_ : current_).field;
  }

 private:
  const TriMesh& mesh_of(const StepData& d) const { return d.mesh ? *d.mesh : *scene_.mesh; }
  // The step after s: the first again where the series loops, else s itself
  // at the end (the last step holds).
  std::size_t following(std::size_t s) const {
    const std::size_t n = scene_.step_count;
    return s + 1 < n ? s + 1 : scene_.scene.loop ? 0 : s;
  }

  void apply(IbfvsRenderer& renderer) {
    const TriMesh& mesh = mesh_of(current_);
    if (&mesh != on_renderer_) {
      // Other triangles on the same points: the points carry the texture on
      // (below); other points: the image-space path (the texture stays in
      // the image).
      if (on_renderer_ && points_correspond(*on_renderer_, mesh))
        renderer.set_triangles(mesh);
      else
        renderer.replace_mesh(mesh, current_.field);
      held_ = current_.mesh;  // keeps a step's own mesh while the renderer shows it
      on_renderer_ = &mesh;
    }
    // Between steps of the same points the points and field are
    // interpolated (whatever their triangles); into a step of other points
    // the current one holds to the end.
    const TriMesh& next_mesh = mesh_of(next_);
    const bool pair = &next_mesh == &mesh || points_correspond(mesh, next_mesh);
    pair_ = pair && next_step_ != step_;
    const StepData& to = pair ? next_ : current_;
    const TriMesh& to_mesh = pair ? next_mesh : mesh;
    const std::vector<glm::vec3>& from = positions_of(current_, mesh);
    const std::vector<glm::vec3>& next = positions_of(to, to_mesh);
    // A surface that moves at either step (or moved before) takes both
    // steps' points, and between them moves along each vertex's fitted
    // screw (core/geometry/rigid_motion.h, over this step's triangles): a
    // rigid part stays rigid.
    if (renderer.moving() || !current_.positions.empty() || !to.positions.empty() || from != next) {
      const SurfaceMotion motion =
          from != next ? fit_surface_motion(mesh.triangles, from, next) : SurfaceMotion{};
      renderer.set_surface_steps(from, normals_of(current_, mesh), next, normals_of(to, to_mesh),
                                 motion);
    }
    renderer.set_field_steps(current_.field, to.field);
    set_scene_scalars(scene_, renderer, current_.color_scalar, current_.beta_scalar);
  }

  const PreparedScene& scene_;
  std::size_t step_ = 0, next_step_ = 1;
  bool pair_ = false;
  float mix_ = 0.0f;
  StepData current_, next_;
  const TriMesh* on_renderer_ = nullptr;
  std::shared_ptr<const TriMesh> held_;
};

double session_time(double t, std::size_t steps, bool loop) {
  if (steps < 2 || !(t > 0.0)) return 0.0;
  const auto n = static_cast<double>(steps);
  return loop ? std::fmod(t, n) : std::min(t, n - 1.0);
}

namespace {

float aspect_of(const PreparedScene& s) {
  return static_cast<float>(s.width) / static_cast<float>(s.height);
}

}  // namespace

Session::Session(PreparedScene scene, std::shared_ptr<const TriMesh> source, std::string name)
    : scene_(std::move(scene)),
      source_(std::move(source)),
      source_name_(std::move(name)),
      camera_(mesh_bounds(*scene_.mesh), scene_.camera, aspect_of(scene_)),
      dt_(scene_.dt) {
  if (scene_.lock_camera)
    lock_camera_.emplace(mesh_bounds(*scene_.mesh), *scene_.lock_camera, aspect_of(scene_));
  load();
}

Session::~Session() = default;

void Session::load() {
  const gl::SavedState saved;
  player_.reset();
  renderer_ = std::make_unique<IbfvsRenderer>(scene_.settings);
  renderer_->set_mesh(*scene_.mesh, scene_.field);
  if (probe_) renderer_->set_probe_length(*probe_);
  renderer_->defer_statistics(defer_statistics_);
  renderer_->record_flow(record_flow_);
  set_scene_scalars(scene_, *renderer_, scene_.color_scalar, scene_.beta_scalar);
  apply_host(true);
  if (!scene_.surface_image.pixels.empty())
    renderer_->set_surface_image(scene_.surface_image, mesh_bounds(*scene_.mesh).centre());
  if (scene_.scene.init == InitMode::RandomCells)
    renderer_->fill_texture_with_cell_colors(scene_.scene.seed);
  player_ = std::make_unique<StepPlayer>(scene_, *renderer_);
  if (scene_.step_count > 1) player_->seek(time_, *renderer_);
}

void Session::rebuild(bool restart) {
  if (restart) {
    load();
    frame_ = 0;
    return;
  }
  // The texture as it is, and the camera that drew it, into the new renderer.
  const gl::SavedState saved;
  const bool drawn = renderer_->frame() > 0;
  const ImageF raw = drawn ? renderer_->read_texture_raw() : ImageF();
  const ViewState view = renderer_->last_view();
  load();
  if (drawn) renderer_->take_texture(raw, view);
}

void Session::restart() {
  settle();
  rebuild(true);
}

void Session::resize(int width, int height) {
  settle();
  if (width == scene_.width && height == scene_.height) return;
  fit_to_size(scene_, width, height);
  camera_.set_aspect(aspect_of(scene_));
  if (lock_camera_) lock_camera_->set_aspect(aspect_of(scene_));
  rebuild(false);
  refit_dt();
}

void Session::fit_dt(const Camera& camera) {
  host_camera_ = camera;
  host_scale_.reset();
  refit_dt();
}

void Session::follow_host(double world_per_pixel, float speed) {
  if (host_scale_ && *host_scale_ == std::pair(world_per_pixel, speed)) return;
  host_scale_.emplace(world_per_pixel, speed);
  host_camera_.reset();
  refit_dt();
}

void Session::refit_dt() {
  const Scene& s = scene_.scene;
  if (s.dt > 0.0f) {
    dt_ = s.dt;
  } else if (host_scale_) {
    const auto [world_per_pixel, speed] = *host_scale_;
    dt_ = scene_dt(s, speed, world_per_pixel);
  } else if (const float d = host_camera_ ? dt_for_pixel_step(scene_.mesh->positions, scene_.field,
                                                              host_camera_->view_projection(),
                                                              scene_.width, scene_.height, s.step)
                                          : 0.0f;
             d > 0.0f) {
    dt_ = d;
  } else {
    // The scene's camera, as prepared and kept fitted (apply_change,
    // fit_to_size): a series' steps are not read again here.
    dt_ = scene_.dt;
  }
}

void Session::seek(double t) {
  settle();
  time_ = session_time(t, scene_.step_count, scene_.scene.loop);
  player_->seek(time_, *renderer_);
}

void Session::render(const Camera& camera) {
  render(ViewState{camera.view(), camera.projection()});
}

void Session::render(const ViewState& view) {
  settle();
  const gl::SavedState saved;
  renderer_->render_frame(view, dt_);
  draw_overlay(view);
  ++frame_;
}

void Session::draw_overlay(const ViewState& view) {
  if (scene_.scene.overlay != Overlay::Topology) {
    overlay_.reset();
    overlay_for_.reset();
    overlay_steps_.reset();
    return;
  }
  const bool steps = scene_.step_count > 1;
  const std::size_t step = steps ? player_->step() : 0, next = steps ? player_->next_step() : 0;
  const std::array<std::size_t, 5> key{data_version_, step, next,
                                       static_cast<std::size_t>(scene_.width),
                                       static_cast<std::size_t>(scene_.height)};
  const glm::ivec2 size(scene_.width, scene_.height);
  const TopologyOptions& options = scene_.scene.topology;
  if (overlay_steps_ && !(overlay_steps_->options == options)) overlay_steps_.reset();
  if (!overlay_ || overlay_for_ != key || !overlay_steps_) {
    // The step shown and the one played into, each found once: playing on,
    // the next step's features (and their ids) become the shown step's.
    OverlaySteps found;
    found.options = options;
    found.version = data_version_;
    found.step = step;
    found.next = next;
    if (overlay_steps_ && overlay_steps_->version == data_version_ &&
        overlay_steps_->next == step) {
      found.first = std::move(overlay_steps_->second);
      found.next_id = overlay_steps_->next_id;
    } else if (overlay_steps_ && overlay_steps_->version == data_version_ &&
               overlay_steps_->step == step) {
      found.first = std::move(overlay_steps_->first);
      found.next_id = overlay_steps_->next_id;
    } else {
      found.first = steps ? find_topology(player_->surface(), player_->field(), options)
                          : find_topology(*scene_.mesh, scene_.field, options);
      found.next_id =
          static_cast<int>(found.first.critical.points.size() + found.first.lines.lines.size());
    }
    if (next != step) {
      found.second = find_topology(player_->next_surface(), player_->next_field(), options);
      // A feature moves at most two significance scales in a step.
      carry_ids(found.first, found.second, found.next_id, 2.0 * found.first.lines.scale);
      overlay_morph_ = morph_steps(found.first, found.second);
    } else {
      found.second = found.first;
      overlay_morph_ = hold(found.first);
    }
    overlay_steps_ = std::move(found);
    if (!overlay_) overlay_ = std::make_unique<TopologyOverlay>();
    overlay_->set(overlay_morph_, size);
    overlay_for_ = key;
  }
  const float mix = steps ? player_->mix() : 0.0f;
  overlay_topology_ = topology_at(overlay_morph_, mix);
  renderer_->draw_over_output([&] { overlay_->draw(view.view, view.projection, size, mix); });
}

void Session::advance() {
  const int k = frame_;
  if (k == scene_.lock_at) {
    renderer_->lock();
    if (lock_camera_) camera_ = *lock_camera_;
  }
  seek(static_cast<double>(k) / scene_.scene.frames_per_step);
  if (k > 0 && scene_.scene.orbit != 0.0f) camera_.orbit(scene_.scene.orbit);
  render(camera_);
}

SetResult Session::set(const Scene& next, const Camera* seen_by, Apply when) {
  // The world units a pixel spans at the mesh centre as the frames are
  // drawn: an object-space noise cell is sized for it.
  const Camera& seen = seen_by ? *seen_by : host_camera_ ? *host_camera_ : camera_;
  const ChangePlan plan = apply_change(scene_, next, seen.world_per_pixel(scene_.height));
  if (plan.prepare) {
    prepare_again(next);
    if (when == Apply::Now) settle();
    return SetResult::Prepared;
  }
  if (plan.camera)
    camera_ = Camera(mesh_bounds(*scene_.mesh), scene_.camera, aspect_of(scene_));
  else if (plan.size)
    camera_.set_aspect(aspect_of(scene_));
  if (plan.size && lock_camera_) lock_camera_->set_aspect(aspect_of(scene_));
  if (plan.camera || plan.size) host_camera_.reset();  // the caller's camera changes: fit_dt
  // The texture resampled to the size and grid (a new seed: afresh).
  owed_.rebuild = owed_.rebuild || plan.regrid || plan.reseed || plan.size;
  owed_.restart = owed_.restart || plan.reseed;
  owed_.settings = true;
  owed_.field = owed_.field || plan.tangent;
  if (plan.reseed) frame_ = 0;
  if (plan.tangent) ++data_version_;
  if (plan.step || plan.tangent || plan.camera || plan.size) refit_dt();
  if (when == Apply::Now) settle();
  return plan.camera || plan.size ? SetResult::NewView : SetResult::Applied;
}

void Session::prepare_again(const Scene& next) {
  PreparedScene prepared =
      source_ ? prepare_scene(next, *source_, source_name_) : prepare_scene(next);
  // The texture goes on over the same surface (a new colour array, field or
  // range); over another surface, or to another start, it starts afresh.
  const TriMesh &from = *scene_.mesh, &to = *prepared.mesh;
  const bool carried = frame_ > 0 && (!owed_.load || owed_.carry) &&
                       next.init == scene_.scene.init && from.triangles == to.triangles &&
                       from.positions == to.positions;
  scene_ = std::move(prepared);
  camera_ = Camera(mesh_bounds(*scene_.mesh), scene_.camera, aspect_of(scene_));
  lock_camera_.reset();
  if (scene_.lock_camera)
    lock_camera_.emplace(mesh_bounds(*scene_.mesh), *scene_.lock_camera, aspect_of(scene_));
  host_camera_.reset();
  host_scale_.reset();
  time_ = 0.0;
  ++data_version_;
  dt_ = scene_.dt;
  owed_ = Owed{};
  owed_.load = true;
  owed_.carry = carried;
  if (!carried) frame_ = 0;
}

void Session::settle() {
  const Owed owed = owed_;
  owed_ = Owed{};
  if (owed.load) {
    // A new renderer for the scene prepared again, the texture carried.
    const gl::SavedState saved;
    const ImageF raw = owed.carry ? renderer_->read_texture_raw() : ImageF();
    const ViewState view = renderer_->last_view();
    load();
    if (owed.carry) renderer_->take_texture(raw, view);
    return;
  }
  if (owed.rebuild)
    rebuild(owed.restart);
  else if (owed.settings)
    apply_host(false);
  if (owed.field) {
    const gl::SavedState saved;
    renderer_->set_field(scene_.field);
  }
}

void Session::set_field(std::vector<glm::vec3> field) {
  if (field.size() != scene_.mesh->vertex_count())
    throw InputError("the field has " + std::to_string(field.size()) + " vectors, the mesh " +
                     std::to_string(scene_.mesh->vertex_count()) + " vertices");
  scene_.field = std::move(field);
  fit_field(scene_);
  ++data_version_;
  settle();
  const gl::SavedState saved;
  renderer_->set_field(scene_.field);
  refit_dt();
}

void Session::set_elements(std::vector<FlowElement> elements) {
  FieldSpec spec = scene_.field_spec.kind == FieldKind::Elements ? scene_.field_spec
                                                                 : FieldSpec::parse("elements");
  spec.elements = std::move(elements);
  for (const FlowElement& e : spec.elements) e.validate();
  std::vector<glm::vec3> field = evaluate_field(*scene_.mesh, spec, scene_.scene.tangent);
  scene_.field_spec = std::move(spec);
  set_field(std::move(field));
}

void Session::change_surface(std::shared_ptr<const TriMesh> mesh, const std::string& name) {
  change_data(prepare_change(scene_, *mesh, name));
  source_ = std::move(mesh);
  source_name_ = name;
}

void Session::present(int window_width, int window_height, int left) {
  renderer_->present(window_width, window_height, left);
}

void Session::draw_to_host(glm::ivec2 origin, bool interior) {
  renderer_->draw_to_host(origin, interior);
}

void Session::finish() {
  renderer_->finish();
}

void Session::apply_host(bool upload) {
  RenderSettings s = scene_.settings;
  if (advect_override_) s.advect_view = *advect_override_;
  if (host_colours_) {
    const HostColours& c = *host_colours_;
    const auto& scalars = scene_.mesh->scalars;
    const auto t = scalars.find(kHostColour);
    const bool coloured = !c.table.empty() && t != scalars.end();
    if (coloured && upload) renderer_->set_scalars(t->second, {});
    s.use_color = coloured;
    s.color_table = coloured ? c.table : std::vector<glm::vec3>{};
    s.color_range = glm::vec2(0.0f, 1.0f);
    s.surface_color = coloured ? c.nan : c.surface;  // NaN positions show the NaN colour
  }
  if (!(s == renderer_->settings())) renderer_->update_settings(s);
}

void Session::lock() {
  settle();
  renderer_->lock();
}

void Session::unlock() {
  renderer_->unlock();
}

void Session::shift_image(glm::vec2 pixels) {
  renderer_->shift_image(pixels);
}

void Session::override_advect_view(std::optional<AdvectView> view) {
  advect_override_ = view;
  apply_host(false);
}

void Session::set_host_colours(const HostColours& colours) {
  if (host_colours_ && *host_colours_ == colours) return;
  const bool table = !host_colours_ || host_colours_->table.empty() != colours.table.empty();
  host_colours_ = colours;
  apply_host(table);
}

void Session::set_probe_length(float world) {
  if (!(world > 0.0f) || !std::isfinite(world) || probe_ == world) return;
  probe_ = world;
  renderer_->set_probe_length(world);
}

void Session::defer_statistics(bool on) {
  defer_statistics_ = on;
  renderer_->defer_statistics(on);
}

void Session::take_composited(const ImageF& texture, const ImageF* output) {
  settle();
  const gl::SavedState saved;
  renderer_->write_texture_raw(texture);
  if (output) {
    renderer_->write_output_raw(*output);
    renderer_->run_deferred_statistics();
  }
}

void Session::record_flow(bool on) {
  record_flow_ = on;
  renderer_->record_flow(on);
}

void FramePacer::set_frames_per_step(int frames) {
  per_step_ = std::clamp(frames, 1, kMaxFramesPerStep);
}

int FramePacer::next(bool changed, bool restart, bool moved, bool carried) {
  if (restart) {
    first_ = true;
    renders_ = 1;
    return per_step_;
  }
  if (!changed) {
    ++renders_;
    return 1;
  }
  const int rendered = moved ? 1 : carried ? renders_ : first_ || renders_ <= 2 ? 1 : renders_;
  const int owed = std::max(per_step_ - rendered, 0);
  first_ = false;
  renders_ = 1;
  return 1 + owed;
}

void Session::change_data(PreparedScene next) {
  settle();
  if (!next.mesh) throw InputError("change_data: no mesh");
  const gl::SavedState saved;
  ++data_version_;
  const TriMesh& from = *scene_.mesh;
  const TriMesh& to = *next.mesh;
  // A series played so far gives way to the new data.
  player_.reset();
  if (points_correspond(from, to)) {
    // The same points (the same triangles, or a few split otherwise): the
    // next frame advects from where the last one drew its points (the
    // renderer keeps them) to the new ones, at once; the frames after it
    // take the texture onto the new flow (docs/paraview.md, "Time": faster
    // than interpolating the change over them).
    if (to.triangles != from.triangles) renderer_->set_triangles(to);
    if (to.positions != from.positions || renderer_->moving())
      renderer_->set_surface_steps(to.positions, to.normals, to.positions, to.normals);
    renderer_->set_field(next.field);
  } else {
    renderer_->replace_mesh(to, next.field);
  }
  set_scene_scalars(scene_, *renderer_, next.color_scalar, next.beta_scalar);
  // The data is the new scene's; the settings, camera and dt stay this session's.
  scene_.mesh = std::move(next.mesh);
  scene_.field = std::move(next.field);
  scene_.color_scalar = std::move(next.color_scalar);
  scene_.beta_scalar = std::move(next.beta_scalar);
  scene_.source_vertices = next.source_vertices;
  scene_.source_topology = next.source_topology;
  scene_.vertex_order = std::move(next.vertex_order);
  scene_.step_count = next.step_count;
  scene_.step_data = std::move(next.step_data);
  player_ = std::make_unique<StepPlayer>(scene_, *renderer_);
  apply_host(true);  // the host's colour positions of the new data
}

}  // namespace ibfvs
