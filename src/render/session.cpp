#include "ibfvs/render/session.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "ibfvs/core/fields/vector_field.h"
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
    renderer.set_field_mix(static_cast<float>(t - static_cast<double>(s)));
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
      // Other triangles: the image-space path (the texture stays in the image).
      renderer.replace_mesh(mesh, current_.field);
      held_ = current_.mesh;  // keeps a step's own mesh while the renderer shows it
      on_renderer_ = &mesh;
    }
    // Between steps of one surface the points and field are interpolated;
    // into a step with other triangles the current one holds to the end.
    const bool pair = &mesh_of(next_) == &mesh;
    const StepData& to = pair ? next_ : current_;
    // A surface that moves at either step (or moved before) takes both
    // steps' points, and between them moves along each vertex's fitted
    // screw (core/geometry/rigid_motion.h): a rigid part stays rigid.
    if (renderer.moving() || !current_.positions.empty() || !to.positions.empty()) {
      const std::vector<glm::vec3>& from = positions_of(current_, mesh);
      const std::vector<glm::vec3>& next = positions_of(to, mesh);
      const SurfaceMotion motion =
          from != next ? fit_surface_motion(mesh.triangles, from, next) : SurfaceMotion{};
      renderer.set_surface_steps(from, normals_of(current_, mesh), next, normals_of(to, mesh),
                                 motion);
    }
    renderer.set_field_steps(current_.field, to.field);
    set_scene_scalars(scene_, renderer, current_.color_scalar, current_.beta_scalar);
  }

  const PreparedScene& scene_;
  std::size_t step_ = 0, next_step_ = 1;
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

Session::Session(PreparedScene scene)
    : scene_(std::move(scene)),
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
  set_scene_scalars(scene_, *renderer_, scene_.color_scalar, scene_.beta_scalar);
  if (!scene_.surface_image.pixels.empty())
    renderer_->set_surface_image(scene_.surface_image, mesh_bounds(*scene_.mesh).centre());
  if (scene_.scene.init == InitMode::RandomCells)
    renderer_->fill_texture_with_cell_colors(scene_.scene.seed);
  player_ = std::make_unique<StepPlayer>(scene_, *renderer_);
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
  if (scene_.step_count > 1) player_->seek(time_, *renderer_);
  if (drawn) renderer_->take_texture(raw, view);
}

void Session::resize(int width, int height) {
  if (width == scene_.width && height == scene_.height) return;
  scene_ = resized(scene_, width, height);
  dt_ = scene_.dt;
  camera_.set_aspect(aspect_of(scene_));
  if (lock_camera_) lock_camera_->set_aspect(aspect_of(scene_));
  rebuild(false);
}

void Session::seek(double t) {
  time_ = session_time(t, scene_.step_count, scene_.scene.loop);
  player_->seek(time_, *renderer_);
}

void Session::render(const Camera& camera) {
  render(ViewState{camera.view(), camera.projection()});
}

void Session::render(const ViewState& view) {
  const gl::SavedState saved;
  renderer_->render_frame(view, dt_);
  ++frame_;
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

bool Session::set(const Scene& next, const Camera* seen_by) {
  const Scene& now = scene_.scene;
  std::set<KeyEffect> effects;
  for (const std::string_view key : changed_keys(now, next)) {
    const KeyEffect effect = change_effect(key, next, scene_.step_count > 1);
    if (effect == KeyEffect::kPrepare) return false;
    effects.insert(effect);
  }
  const auto has = [&](KeyEffect e) { return effects.count(e) > 0; };

  // Everything checked before anything changes.
  RenderSettings settings = renderer_->settings();
  apply_texture_settings(next, settings);
  settings.noise.scale = next.scale;
  settings.noise.seed = next.seed;
  if (settings.object_noise && !renderer_->settings().object_noise) {
    // s pixels at the distance of the mesh centre, as prepare_scene does.
    const Camera& c = seen_by ? *seen_by : camera_;
    settings.object_cell = settings.noise.scale * c.world_per_pixel(scene_.height);
  }
  {
    RenderSettings sized = settings;  // the size too, before anything changes
    sized.width = next.width;
    sized.height = next.height;
    sized.validate();
  }
  std::vector<glm::vec3> field;
  if (has(KeyEffect::kTangent))
    field = evaluate_field(*scene_.mesh, scene_.field_spec, next.tangent);

  const float step_ratio = now.step > 0.0f ? next.step / now.step : 1.0f;
  const bool reseeded = next.seed != now.seed;
  scene_.scene = next;
  scene_.settings = settings;
  // A new view: dt (the step is in pixels) and the object-space cell for it.
  const bool refit = has(KeyEffect::kCamera) && !has(KeyEffect::kSize);
  if (has(KeyEffect::kCamera)) {
    CameraParams params = next.camera;
    params.up = scene_.camera.up;  // the prepared scene's up (a key of its own)
    scene_.camera = params;
    camera_ = Camera(mesh_bounds(*scene_.mesh), params, aspect_of(scene_));
    if (refit) {
      scene_ = resized(scene_, scene_.width, scene_.height);
      dt_ = scene_.dt;
    }
  }
  if (has(KeyEffect::kNoise))
    rebuild(reseeded);
  else
    renderer_->update_settings(scene_.settings);
  if (has(KeyEffect::kTangent)) set_field(std::move(field));
  if (has(KeyEffect::kSize))
    resize(next.width, next.height);  // dt from the new size, view and step
  else if (has(KeyEffect::kStep) && !refit)
    dt_ *= step_ratio;
  return true;
}

void Session::set_field(std::vector<glm::vec3> field) {
  if (field.size() != scene_.mesh->vertex_count())
    throw InputError("the field has " + std::to_string(field.size()) + " vectors, the mesh " +
                     std::to_string(scene_.mesh->vertex_count()) + " vertices");
  scene_.field = std::move(field);
  const gl::SavedState saved;
  renderer_->set_field(scene_.field);
}

void FramePacer::set_frames_per_step(int frames) {
  per_step_ = std::clamp(frames, 1, kMaxFramesPerStep);
}

int FramePacer::next(bool changed, bool restart, bool moved) {
  if (restart) {
    first_ = true;
    renders_ = 1;
    return per_step_;
  }
  if (!changed) {
    ++renders_;
    return 1;
  }
  const int rendered = first_ || moved || renders_ <= 2 ? 1 : renders_;
  const int owed = std::max(per_step_ - rendered, 0);
  first_ = false;
  renders_ = 1;
  return 1 + owed;
}

void Session::change_data(PreparedScene next) {
  if (!next.mesh) throw InputError("change_data: no mesh");
  const gl::SavedState saved;
  const TriMesh& from = *scene_.mesh;
  const TriMesh& to = *next.mesh;
  // A series played so far gives way to the new data.
  player_.reset();
  if (to.vertex_count() == from.vertex_count() && to.triangles == from.triangles) {
    // The same surface: the next frame advects from where the last one drew
    // its points (the renderer keeps them) to the new ones, at once; the
    // frames after it take the texture onto the new flow (docs/paraview.md,
    // "Time": faster than interpolating the change over them).
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
}

}  // namespace ibfvs
