#include "ibfvs/viewer_state.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibfvs/core/error.h"
#include "ibfvs/core/vector_field.h"

namespace ibfvs::app {

DragMode parse_drag_mode(const std::string& text) {
  if (text == "plain") return DragMode::Plain;
  if (text == "translate") return DragMode::Translate;
  if (text == "freeze") return DragMode::Freeze;
  if (text == "previous") return DragMode::Previous;
  throw InputError("--drag: expected plain, translate, freeze or previous, got '" + text + "'");
}

std::string to_string(DragMode mode) {
  switch (mode) {
    case DragMode::Plain:
      return "plain";
    case DragMode::Translate:
      return "translate";
    case DragMode::Freeze:
      return "freeze";
    case DragMode::Previous:
      return "previous";
  }
  return "?";
}

ViewerCamera::ViewerCamera(const Bounds& bounds, const CameraParams& start, float aspect)
    : bounds_(bounds), start_(start), params_(start), aspect_(aspect) {
  Camera check(bounds_, params_, aspect_);  // throws for impossible settings
}

void ViewerCamera::rotate(glm::vec2 pixels) {
  constexpr float kDegreesPerPixel = 0.3f;
  params_.azimuth_deg = std::fmod(params_.azimuth_deg - pixels.x * kDegreesPerPixel, 360.0f);
  params_.elevation_deg =
      std::clamp(params_.elevation_deg - pixels.y * kDegreesPerPixel, -89.0f, 89.0f);
}

void ViewerCamera::zoom(float steps) {
  const float diagonal = std::max(bounds_.diagonal(), 1e-6f);
  // Distance 0 means "fitted": start from the fitted distance.
  const float now = camera().distance_world() / diagonal;
  params_.distance = std::clamp(now * std::pow(0.9f, steps), 0.01f, 100.0f);
}

void ViewerCamera::pan(glm::vec2 pixels, int height) {
  const Camera c = camera();
  const float world_per_pixel = 2.0f * c.distance_world() *
                                std::tan(glm::radians(params_.fov_deg) * 0.5f) /
                                static_cast<float>(std::max(height, 1));
  const glm::mat4 view = c.view();
  // Rows of the view matrix: the camera's right and up axes in world space.
  const glm::vec3 right(view[0][0], view[1][0], view[2][0]);
  const glm::vec3 up(view[0][1], view[1][1], view[2][1]);
  params_.target -= world_per_pixel * (pixels.x * right + pixels.y * up);
}

void ViewerCamera::recentre(const glm::vec3& point) {
  params_.target = point - bounds_.centre();
}

void ViewerCamera::reset() {
  params_ = start_;
}

std::vector<ScriptAction> read_script(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open the script");
  // Verb -> number of arguments.
  static const std::map<std::string, int> arity = {
      {"drag", 3},    {"zoom", 1},   {"pan", 2},        {"set", 2},     {"mode", 1},
      {"lock", 0},    {"unlock", 0}, {"screenshot", 1}, {"texture", 1}, {"save", 1},
      {"quit", 0},    {"window", 1}, {"help", 0},       {"style", 1},   {"load", 1},
      {"element", 1}, {"record", 0}, {"snapshot", 2}};
  std::vector<ScriptAction> actions;
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    const std::string where = path.string() + ":" + std::to_string(line_number);
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string frame_text;
    if (!(words >> frame_text)) continue;
    ScriptAction a;
    try {
      a.frame = parse_int(frame_text, where + ": the frame", 0, 100000000);
    } catch (const InputError& e) {
      throw InputError(e.what());
    }
    if (!(words >> a.verb)) throw InputError(where + ": a frame needs an action");
    const auto it = arity.find(a.verb);
    if (it == arity.end())
      throw InputError(where + ": unknown action '" + a.verb +
                       "' (drag, zoom, pan, set, mode, lock, unlock, screenshot, window, texture, "
                       "save, style, load, element, record, snapshot, help, quit)");
    for (std::string w; words >> w;) a.args.push_back(w);
    if (static_cast<int>(a.args.size()) != it->second)
      throw InputError(where + ": '" + a.verb + "' takes " + std::to_string(it->second) +
                       " argument(s), got " + std::to_string(a.args.size()));
    if (!actions.empty() && a.frame < actions.back().frame)
      throw InputError(where + ": frames must not decrease");
    if (a.verb == "drag") {
      parse_numbers(a.args[0] + "," + a.args[1], where + ": drag");
      parse_int(a.args[2], where + ": drag frames", 1, 100000);
    } else if (a.verb == "zoom") {
      parse_numbers(a.args[0], where + ": zoom", 1);
    } else if (a.verb == "pan") {
      parse_numbers(a.args[0] + "," + a.args[1], where + ": pan", 2);
    } else if (a.verb == "mode") {
      try {
        parse_drag_mode(a.args[0]);
      } catch (const InputError& e) {
        throw InputError(where + ": " + e.what());
      }
    }
    actions.push_back(std::move(a));
  }
  return actions;
}

}  // namespace ibfvs::app
