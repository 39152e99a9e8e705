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
  {
    RenderSettings check;  // every value checked before anything changes
    apply_texture_settings(s, check);
    check.validate();
  }
  bool restart = false, regrid = false, live = false;
  for (const std::string_view key : changed_keys(scene_, s)) {
    switch (change_effect(key, s, false)) {
      case KeyEffect::kLive:
      case KeyEffect::kStep:
        live = true;
        break;
      case KeyEffect::kNoise:
        (key == "scale" ? regrid : restart) = true;
        break;
      default:
        restart = true;  // a key the texture cannot take on: it starts afresh
    }
  }
  scene_ = std::move(s);
  restart_ = restart_ || restart;
  regrid_ = regrid_ || regrid;
  settings_changed_ = settings_changed_ || live;
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
  const bool moved = last && last->triangles == mesh.triangles && last->positions != mesh.positions;
  mesh_ = std::make_shared<const TriMesh>(std::move(mesh));
  name_ = name;
  speed_ = speed;
  const Bounds b = mesh_bounds(*mesh_);
  bounds_ = {b.min, b.max};
  data_changed_ = true;
  points_moved_ = points_moved_ || moved;
  colours_changed_ = true;
}

void HostFlow::set_colours(HostColours colours) {
  if (colours == colours_) return;
  colours_ = std::move(colours);
  colours_changed_ = true;
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
  c.regrid = regrid_;
  c.changed = data_changed_;
  c.moved = points_moved_;
  c.speed = speed_;
  if (mesh_) c.bounds = bounds_;
  return c;
}

// The session made (a restart, the first surface), dropped (no surface), or
// taking on a new size, noise grid or data, as agreed: the texture goes on
// from where it is, only a restart starts it afresh.
void HostFlow::update_session(int width, int height, const HostChanges& all) {
  const bool new_renderer = all.restart || all.resize || all.regrid;
  try {
    if (all.restart || (!mesh_ && session_)) {
      session_.reset();
      frame_ = 0;
      if (mesh_) {
        Scene s = scene_;
        s.width = width;
        s.height = height;
        session_ = std::make_unique<Session>(prepare_scene(s, *mesh_, name_));
        made_in_ = gl::current_context();
      }
    } else if (session_) {
      if (all.resize) session_->resize(width, height);
      if (all.regrid) {
        session_->scene().scene.scale = scene_.scale;
        session_->scene().settings.noise.scale = scene_.scale;
        session_->rebuild(false);
      }
      if (data_changed_ && mesh_)
        session_->change_data(prepare_change(session_->scene(), *mesh_, name_));
    }
  } catch (const std::exception& e) {
    // No texture from this surface: the host's other processes go on (this
    // one as an empty piece) until their next agreement.
    failure_ = std::current_exception();
    problem_ = e.what();
    session_.reset();
  }
  if (new_renderer || all.changed) {
    settings_changed_ = true;  // a new renderer, or new data: the settings and colours again
    colours_changed_ = true;
  }
  if (new_renderer) renderer_frame_ = 0;
  width_ = width;
  height_ = height;
  restart_ = regrid_ = data_changed_ = points_moved_ = false;
}

// The texture settings, the host's colours and dt for this render.
void HostFlow::apply_settings(const HostRender& r, const HostChanges& all) {
  IbfvsRenderer& renderer = session_->renderer();
  if (settings_changed_) {
    // The probe for the surface's motion, from the bounds of every piece:
    // once for a new renderer, size or surface, not at every render.
    const float diagonal = all.diagonal();
    if (diagonal > 0.0f && std::isfinite(diagonal)) renderer.set_probe_length(1e-3f * diagonal);
  }
  RenderSettings settings = renderer.settings();
  const RenderSettings before = settings;
  apply_texture_settings(scene_, settings);
  settings.surface_color = r.surface_color;
  const auto& prepared = session_->scene().mesh->scalars;
  const auto t = prepared.find(kHostColour);
  const bool coloured = !colours_.table.empty() && t != prepared.end();
  if (coloured && colours_changed_) renderer.set_scalars(t->second, {});
  colours_changed_ = false;
  if (coloured) settings.surface_color = colours_.nan;  // what NaN positions show
  settings.use_color = coloured;
  settings.color_table = coloured ? colours_.table : std::vector<glm::vec3>{};
  settings.color_range = glm::vec2(0.0f, 1.0f);
  if (settings_changed_ || settings.use_color != before.use_color ||
      settings.color_table != before.color_table ||
      settings.surface_color != before.surface_color) {
    renderer.update_settings(settings);
    settings_changed_ = false;
  }
  // dt: the fastest vector of the whole surface moves `step` pixels at the
  // focal point (every vector does, normalised in image space).
  // Normalised, any dt > 0 moves every point `step` pixels: 1 where anything moves.
  const bool moves = scene_.step > 0.0f && all.speed > 0.0f;
  session_->set_dt(scene_.image_normalize ? (moves ? 1.0f : 0.0f)
                                          : dt_for_step(scene_.step, all.speed, r.world_per_pixel));
  renderer.defer_statistics(r.defer_statistics);
}

int HostFlow::begin(const HostRender& r, const HostChanges& all) {
  failure_ = nullptr;
  problem_.clear();
  const int frames =
      pacer_.next(all.changed || all.restart, all.restart,
                  all.moved && !carries_surface(scene_.advect_view, scene_.field_frame));
  update_session(std::max(r.width, 1), std::max(r.height, 1), all);
  if (session_) apply_settings(r, all);
  return frames;
}

void HostFlow::frame(const ViewState& view) {
  if (session_) session_->render(view);
  ++frame_;
  ++renderer_frame_;
}

void HostFlow::finish(glm::ivec2 origin, bool within_surface) {
  if (session_) session_->renderer().draw_to_host(origin, within_surface);
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
