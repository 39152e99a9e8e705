#include "ibfvs/render/host_flow.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

#include "ibfvs/core/geometry/displacement.h"
#include "ibfvs/core/scene/render_settings.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/context.h"

namespace ibfvs {

HostFlow::HostFlow() {
  scene_.field = FieldSpec::parse("file");
}

HostFlow::~HostFlow() {
  // The objects are deleted where the context they were made in is current;
  // elsewhere there is nothing to delete them in, and they go with that
  // context (a host releases before it closes).
  if (session_ && gl::current_context() != made_in_) static_cast<void>(session_.release());
}

void HostFlow::set_scene(const Scene& next) {
  Scene s = next;
  s.field = scene_.field;
  s.width = scene_.width;
  s.height = scene_.height;
  if (session_) {
    // The session's one door, now: it checks, plans and takes the change
    // (throwing SettingError, changing nothing); the GPU's part waits for
    // the host's next render, where its context is current.
    Scene at = s;
    at.width = session_->scene().width;
    at.height = session_->scene().height;
    if (session_->set(at, nullptr, Apply::AtNextFrame) == SetResult::Prepared &&
        session_->frame() == 0)
      frame_ = 0;  // prepared again over another surface: afresh
  } else {
    static_cast<void>(scene_settings(s, RenderSettings{}));  // checked; the first session's
  }
  // A new seed starts the texture afresh on every process alike (the
  // host's agreement: restart), those with an empty piece too.
  restart_ = restart_ || s.seed != scene_.seed;
  scene_ = std::move(s);
}

void HostFlow::set_frames_per_step(int frames) {
  pacer_.set_frames_per_step(frames);
}

void HostFlow::set_surface(TriMesh mesh, const std::string& name) {
  validate_mesh(mesh, name);
  if (mesh.vectors.size() != mesh.positions.size())
    throw InputError(name + ": " + std::to_string(mesh.vectors.size()) + " vectors for " +
                     std::to_string(mesh.positions.size()) + " points");
  float speed = 0.0f;
  for (const glm::vec3& v : mesh.vectors)
    if (const float l = glm::length(v); std::isfinite(l)) speed = std::max(speed, l);
  const std::shared_ptr<const TriMesh>& last = mesh_;
  const bool same = last && last->positions == mesh.positions &&
                    last->triangles == mesh.triangles && last->vectors == mesh.vectors &&
                    last->scalars == mesh.scalars && last->normals == mesh.normals;
  if (same) return;
  const bool moved = last && last->positions != mesh.positions && points_correspond(*last, mesh);
  mesh_ = std::make_shared<const TriMesh>(std::move(mesh));
  name_ = name;
  speed_ = speed;
  const Bounds b = mesh_bounds(*mesh_);
  bounds_ = {b.min, b.max};
  data_changed_ = true;
  points_moved_ = points_moved_ || moved;
}

void HostFlow::set_colours(HostColours colours) {
  colours_ = std::move(colours);
}

void HostFlow::clear_surface() {
  if (!mesh_) return;
  mesh_.reset();
  speed_ = 0.0f;
  data_changed_ = true;
}

void HostFlow::restart() {
  restart_ = true;
}

void HostFlow::release() {
  session_.reset();
  restart_ = true;
}

float HostChanges::diagonal() const {
  return bounds ? glm::length(bounds->second - bounds->first) : 0.0f;
}

HostChanges HostFlow::pending(int width, int height) const {
  HostChanges c;
  c.restart = restart_ || (mesh_ && !session_);
  c.resize = std::max(width, 1) != width_ || std::max(height, 1) != height_;
  c.changed = data_changed_;
  c.moved = points_moved_;
  c.speed = speed_;
  if (mesh_) c.bounds = bounds_;
  return c;
}

// The session made (the first surface, with the keys set so far), dropped
// (no surface), or taking on a new size, new data and a restart, as
// agreed: the texture goes on from where it is, only a restart starts it
// afresh. The keys went to the session when they were set (set_scene).
void HostFlow::update_session(int width, int height, const HostChanges& all) {
  try {
    if (!mesh_) {
      if (session_ || all.restart) frame_ = 0;
      session_.reset();
    } else if (!session_) {
      frame_ = 0;
      Scene s = scene_;
      s.width = width;
      s.height = height;
      session_ = std::make_unique<Session>(prepare_scene(s, *mesh_, name_), mesh_, name_);
      made_in_ = gl::current_context();
    } else {
      if (all.resize) session_->resize(width, height);
      if (data_changed_) session_->change_surface(mesh_, name_);
      // Every process starts afresh where one does (a first surface, a new
      // seed): their frame counts stay alike. A new seed has already.
      if (all.restart && session_->frame() > 0) session_->restart();
      if (all.restart) frame_ = 0;
    }
  } catch (const std::exception& e) {
    // No texture from this surface: the host's other processes go on (this
    // one as an empty piece) until their next agreement.
    failure_ = std::current_exception();
    problem_ = e.what();
    session_.reset();
  }
  width_ = width;
  height_ = height;
  restart_ = data_changed_ = points_moved_ = false;
}

// The host's view and colours for this render, through the session's door.
void HostFlow::apply_host(const HostRender& r, const HostChanges& all) {
  // The probe for the surface's motion, from the bounds of every piece.
  session_->set_probe_length(1e-3f * all.diagonal());
  HostColours colours = colours_;
  colours.surface = r.surface_color;
  session_->set_host_colours(colours);
  // dt: the fastest vector of the whole surface moves `step` pixels at the
  // focal point.
  session_->follow_host(world_per_pixel(r.view.projection, r.focal_distance, r.height), all.speed);
  session_->defer_statistics(r.defer_statistics);
}

int HostFlow::begin(const HostRender& r, const HostChanges& all) {
  failure_ = nullptr;
  problem_.clear();
  const bool carries = carries_surface(scene_.advect_view, scene_.field_frame);
  const int frames = pacer_.next(all.changed || all.restart, all.restart, all.moved && !carries,
                                 all.moved && carries);
  update_session(std::max(r.width, 1), std::max(r.height, 1), all);
  if (session_) apply_host(r, all);
  return frames;
}

void HostFlow::frame(const ViewState& view) {
  if (session_) session_->render(view);
  ++frame_;
}

void HostFlow::finish(glm::ivec2 origin, bool within_surface) {
  if (session_) session_->draw_to_host(origin, within_surface);
}

void HostFlow::render(const HostRender& r) {
  if (!mesh_) throw InputError("no surface to draw the texture on (set_surface)");
  if (const int v = gl::current_gl_version(); v < 45)
    throw GraphicsError(v == 0 ? std::string("no OpenGL context is current: the host draws in its "
                                             "own (render in its render callback)")
                               : "needs OpenGL 4.5 (the host's context has " +
                                     std::to_string(v / 10) + "." + std::to_string(v % 10) + ")");
  const int frames = begin(r, pending(r.width, r.height));
  if (failure_) std::rethrow_exception(failure_);
  for (int k = 0; k < frames; ++k) frame(r.view);
  finish(r.origin);
}

}  // namespace ibfvs
