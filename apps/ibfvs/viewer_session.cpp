#include "ibfvs/viewer_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include "ibfvs/core/image/image.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"

namespace ibfvs::app {
namespace {

float aspect_of(const PreparedScene& s) {
  return static_cast<float>(s.width) / static_cast<float>(s.height);
}

}  // namespace

ViewerSession::ViewerSession(Scene desc, PreparedScene prepared, DragMode drag)
    : drag_mode(drag),
      desc_(std::move(desc)),
      session_(std::make_unique<Session>(std::move(prepared))),
      camera_(mesh_bounds(*scene().mesh), scene().camera, aspect_of(scene())) {}

ViewerSession::~ViewerSession() {
  if (video_) video_->close();
}

void ViewerSession::frame() {
  if (paused) return;
  if (scene().step_count > 1) {
    time += 1.0 / desc_.frames_per_step;
    session_->seek(time);
    time = session_->time();  // on from the first step, or held at the last (loop)
  }
  session_->render(camera_.camera());
  if (video_) {
    ImageU8 image = video_->spare();
    session_->read_output(image);
    video_->write(std::move(image));
  }
}

// ------------------------------------------------------------ the scene

bool ViewerSession::reload(const Scene& desc) {
  try {
    apply_live(desc);
    return true;
  } catch (const std::exception&) {
    return false;  // apply_live said why (message)
  }
}

void ViewerSession::apply_style(Style style) {
  Scene desc = desc_;
  ibfvs::apply_style(desc, style);  // the preset wins over what is in force
  if (reload(desc)) message = "style " + std::string(enum_name(style));
}

void ViewerSession::load(const std::string& path) {
  if (is_scene_path(path)) {
    try {
      reload(read_scene(path));
    } catch (const std::exception& e) {
      message = std::string("error: ") + e.what();
    }
    return;
  }
  Scene desc = desc_;
  desc.mesh = path;
  desc.field_steps.clear();
  reload(desc);
}

void ViewerSession::set(const std::string& key, const std::string& value) {
  Scene desc = desc_;
  apply_setting(desc, key, value);
  apply_live(desc);
}

void ViewerSession::apply_live(const Scene& desc) {
  // The session's rules (Session::set): the viewer keeps only its own
  // camera, made again where the view changed.
  const Camera view = camera_.camera();
  SetResult result = SetResult::Applied;
  try {
    result = session_->set(desc, &view);
  } catch (const std::exception& e) {  // nothing changed: the old scene stays
    message = std::string("error: ") + e.what();
    std::fprintf(stderr, "ibfvs: %s\n", message.c_str());
    throw;
  }
  switch (result) {
    case SetResult::Prepared:
      desc_ = desc;
      prepared_again();
      return;
    case SetResult::NewView:
      camera_ = ViewerCamera(mesh_bounds(*scene().mesh), scene().camera, aspect_of(scene()));
      update_dt();
      break;
    case SetResult::Applied:
      break;
  }
  desc_ = desc;
}

void ViewerSession::prepared_again() {
  for (const std::string& w : scene().warnings)
    std::fprintf(stderr, "ibfvs: warning: %s\n", w.c_str());
  camera_ = ViewerCamera(mesh_bounds(*scene().mesh), scene().camera, aspect_of(scene()));
  selected_element = -1;
  time = 0.0;
  message = "loaded " + scene().mesh_name;
}

void ViewerSession::restart() {
  session_->restart();
  message = "restarted";
}

void ViewerSession::set_noise_scale(float scale) {
  Scene desc = desc_;
  desc.scale = scale;
  apply_live(desc);
}

void ViewerSession::set_tangent(TangentMode mode) {
  Scene desc = desc_;
  desc.tangent = mode;
  apply_live(desc);
}

void ViewerSession::save_scene(const std::filesystem::path& file) {
  Scene desc = desc_;
  const CameraParams& p = camera_.params();
  const float diagonal = std::max(camera_.bounds().diagonal(), 1e-6f);
  desc.camera.azimuth_deg = p.azimuth_deg;
  desc.camera.elevation_deg = p.elevation_deg;
  desc.camera.distance = p.distance > 0.0f ? camera_.camera().distance_world() / diagonal : 0.0f;
  desc.camera.target = p.target;
  desc.frames = std::max(frame_count(), 1);
  desc.width = scene().width;
  desc.height = scene().height;
  if (desc.lock_at == Scene::kLockAuto) desc.lock_at = scene().lock_at;
  PendingFile pending(file);  // whole or not at all
  std::ofstream out(pending.temporary());
  out << scene_toml(desc);
  out.close();
  if (!out) throw InputError(file.string() + ": cannot write the scene");
  pending.commit();
  std::printf("ibfvs: saved %s (frame %d)\n", file.c_str(), frame_count());
}

// ------------------------------------------------------------ flow elements

void ViewerSession::add_element(const FlowElement& element) {
  element.validate();
  std::vector<FlowElement> kept = elements();
  kept.push_back(element);
  selected_element = static_cast<int>(kept.size()) - 1;
  set_elements(std::move(kept));
}

std::vector<FlowElement> ViewerSession::elements() const {
  const FieldSpec& spec = scene().field_spec;
  return spec.kind == FieldKind::Elements ? spec.elements : std::vector<FlowElement>{};
}

void ViewerSession::set_elements(std::vector<FlowElement> elements) {
  const bool became = scene().field_spec.kind != FieldKind::Elements;
  try {
    session_->set_elements(std::move(elements));  // dt fits the field
    if (became) message = "the field is now the flow elements";
    // The typed scene follows, so that saving keeps the edited elements.
    const FieldSpec& spec = scene().field_spec;
    desc_.field = spec;
    desc_.field->elements.clear();
    desc_.elements = spec.elements;
  } catch (const std::exception& e) {
    message = std::string("error: ") + e.what();
  }
}

// ------------------------------------------------------------ mouse

void ViewerSession::begin_drag() {
  dragging_ = true;
  if (drag_mode == DragMode::Freeze && !session_->locked()) {
    session_->lock();
    locked_by_drag_ = true;
  }
  session_->override_advect_view(drag_mode == DragMode::Previous ? AdvectView::Previous
                                                                 : AdvectView::Current);
}

void ViewerSession::drag_by(glm::vec2 pixels, bool pan) {
  if (pan)
    camera_.pan(pixels, scene().height);
  else
    camera_.rotate(pixels);
  // The paper's option (b): move F_t and G with the pointer (exact for a pan).
  if (drag_mode == DragMode::Translate) session_->shift_image(pixels);
}

void ViewerSession::end_drag() {
  dragging_ = false;
  if (locked_by_drag_) {
    session_->unlock();
    locked_by_drag_ = false;
  }
  session_->override_advect_view(std::nullopt);
}

void ViewerSession::zoom(float steps) {
  camera_.zoom(steps);
  update_dt();
}

void ViewerSession::pan(glm::vec2 pixels) {
  camera_.pan(pixels, scene().height);
}

std::optional<glm::vec3> ViewerSession::surface_point(glm::vec2 pixel) {
  const int w = scene().width, h = scene().height;
  const int px = static_cast<int>(std::floor(pixel.x));
  const int py = h - 1 - static_cast<int>(std::floor(pixel.y));
  if (px < 0 || py < 0 || px >= w || py >= h) return std::nullopt;
  const ImageF depth = session_->read_depth();
  const float z = depth.pixels[static_cast<std::size_t>(py) * w + px];
  if (z >= 1.0f) return std::nullopt;  // background
  const Camera c = camera_.camera();
  const glm::vec4 ndc(2.0f * (px + 0.5f) / w - 1.0f, 2.0f * (py + 0.5f) / h - 1.0f, 2.0f * z - 1.0f,
                      1.0f);
  const glm::vec4 world = glm::inverse(c.view_projection()) * ndc;
  return glm::vec3(world) / world.w;
}

// The fastest motion back to `step` pixels a frame, after a zoom (which
// would stretch it): the session's rule for the viewer's camera.
void ViewerSession::update_dt() {
  session_->fit_dt(camera_.camera());
}

// ------------------------------------------------------------ texture and outputs

void ViewerSession::toggle_lock() {
  if (session_->locked())
    session_->unlock();
  else
    session_->lock();
}

void ViewerSession::screenshot(const std::filesystem::path& file) {
  write_png(session_->read_output(), file);
  std::printf("ibfvs: wrote %s\n", file.c_str());
}

void ViewerSession::write_texture(const std::filesystem::path& file) {
  write_png16(session_->read_texture().select_channels(0, 3), file);
}

void ViewerSession::toggle_recording() {
  if (video_) {
    video_->close();
    video_.reset();
    message = "recording saved";
    return;
  }
  const std::string name = numbered_name(".mp4");
  try {
    video_ = std::make_unique<VideoWriter>(name, scene().width, scene().height, 30.0);
    message = "recording " + name;
  } catch (const std::exception& e) {
    message = std::string("error: ") + e.what();
  }
}

void ViewerSession::snapshot(int width, int height, const std::filesystem::path& file, int frames) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw InputError("snapshot: the size must be within 1..16384 pixels");
  Session offscreen(resized(scene(), width, height));  // the live changes are the scene's
  ViewerCamera cam = camera_;
  cam.set_aspect(static_cast<float>(width) / static_cast<float>(height));
  const Camera c = cam.camera();
  offscreen.fit_dt(c);  // the same pixels per frame as the window
  offscreen.seek(time);
  for (int k = 0; k < frames; ++k) offscreen.render(c);
  write_png(offscreen.read_output(), file);
  message = "wrote " + file.string();
  std::printf("ibfvs: wrote %s (%dx%d)\n", file.c_str(), width, height);
}

std::string ViewerSession::numbered_name(const char* extension) {
  char name[64];
  std::snprintf(name, sizeof name, "ibfvs-view-%04d%s", numbered_++, extension);
  return name;
}

}  // namespace ibfvs::app
