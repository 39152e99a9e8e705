#include "ibfvs/render/session.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/objects.h"

namespace ibfvs {

// Plays an unsteady field: the current and next steps on the GPU and the mix
// between them. Does nothing for a steady field.
class Session::FieldPlayer {
 public:
  FieldPlayer(const PreparedScene& scene, IbfvsRenderer& renderer) : scene_(scene) {
    if (scene.step_count < 2) return;
    field_ = scene.field;
    next_ = scene.step_field(1 % scene.step_count);
    renderer.set_field_steps(field_, next_);
  }

  // Time t in steps (looping); evaluates a step only when t leaves the current one.
  void seek(double t, IbfvsRenderer& renderer) {
    const std::size_t n = scene_.step_count;
    if (n < 2) return;
    t = std::fmod(std::max(t, 0.0), static_cast<double>(n));
    const auto s = static_cast<std::size_t>(t) % n;
    if (s != step_) {
      // Playing on, the next step is already at hand; a jump evaluates both.
      field_ = s == (step_ + 1) % n ? std::move(next_) : scene_.step_field(s);
      next_ = scene_.step_field((s + 1) % n);
      step_ = s;
      renderer.set_field_steps(field_, next_);
    }
    renderer.set_field_mix(static_cast<float>(t - std::floor(t)));
  }

 private:
  const PreparedScene& scene_;
  std::size_t step_ = 0;
  std::vector<glm::vec3> field_, next_;
};

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
  if (scene_.settings.use_color || scene_.settings.use_beta)
    renderer_->set_scalars(scene_.color_scalar, scene_.beta_scalar);
  if (!scene_.surface_image.pixels.empty())
    renderer_->set_surface_image(scene_.surface_image, mesh_bounds(*scene_.mesh).centre());
  if (scene_.scene.init == InitMode::RandomCells)
    renderer_->fill_texture_with_cell_colors(scene_.scene.seed);
  player_ = std::make_unique<FieldPlayer>(scene_, *renderer_);
}

void Session::rebuild() {
  load();
  frame_ = 0;
}

void Session::seek(double t) {
  player_->seek(t, *renderer_);
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

void Session::set_field(std::vector<glm::vec3> field) {
  if (field.size() != scene_.mesh->vertex_count())
    throw InputError("the field has " + std::to_string(field.size()) + " vectors, the mesh " +
                     std::to_string(scene_.mesh->vertex_count()) + " vertices");
  scene_.field = std::move(field);
  const gl::SavedState saved;
  renderer_->set_field(scene_.field);
}

}  // namespace ibfvs
