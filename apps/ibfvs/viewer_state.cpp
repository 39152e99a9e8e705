#include "ibfvs/viewer_state.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "ibfvs/core/error.h"
#include "ibfvs/core/scene.h"
#include "ibfvs/core/text.h"

namespace ibfvs::app {

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

const std::vector<ScriptVerb>& script_verbs() {
  static const std::vector<ScriptVerb> verbs = {
      {"drag", 3, "DX DY FRAMES: a mouse drag spread over FRAMES frames, through the drag mode"},
      {"zoom", 1, "STEPS: mouse-wheel steps"},
      {"pan", 2, "DX DY: pan by pixels"},
      {"set", 2, "KEY VALUE: any scene key (alpha, step, color_map, mesh, ...)"},
      {"mode", 1, "the drag mode: " + enum_name_list<DragMode>()},
      {"lock", 0, "lock the texture (3.7)"},
      {"unlock", 0, "resume the animation"},
      {"screenshot", 1, "FILE.png: the image"},
      {"window", 1, "FILE.png: the window with the panel"},
      {"texture", 1, "FILE.png: F_t, 16 bits"},
      {"save", 1, "SCENE.toml: the current state as a scene"},
      {"style", 1, "a style: " + enum_name_list<Style>()},
      {"load", 1, "MESH or SCENE.toml"},
      {"element", 1, "AX,AY,AZ,BX,BY,BZ,ROT,RAD,TAN[,CORE]: add a flow element"},
      {"record", 0, "start or stop recording an MP4"},
      {"snapshot", 2, "W,H FILE.png: the current state rendered offscreen at that size"},
      {"help", 0, "show or hide the help"},
      {"quit", 0, "close the window"},
  };
  return verbs;
}

const ScriptVerb* find_script_verb(std::string_view name) {
  for (const ScriptVerb& v : script_verbs())
    if (v.name == name) return &v;
  return nullptr;
}

std::string script_verb_names() {
  std::string out;
  for (const ScriptVerb& v : script_verbs()) out += (out.empty() ? "" : ", ") + v.name;
  return out;
}

std::vector<ScriptAction> read_script(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open the script");
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
      a.frame = static_cast<int>(parse_integer(frame_text, 0, 100000000));
    } catch (const InputError& e) {
      throw InputError(where + ": the frame " + e.what());
    }
    if (!(words >> a.verb)) throw InputError(where + ": a frame needs an action");
    const ScriptVerb* verb = find_script_verb(a.verb);
    if (!verb)
      throw InputError(where + ": unknown action '" + a.verb + "' (" + script_verb_names() + ")");
    for (std::string w; words >> w;) a.args.push_back(w);
    if (a.args.size() != verb->arguments)
      throw InputError(where + ": '" + a.verb + "' takes " + std::to_string(verb->arguments) +
                       " argument(s), got " + std::to_string(a.args.size()));
    if (!actions.empty() && a.frame < actions.back().frame)
      throw InputError(where + ": frames must not decrease");
    try {
      if (a.verb == "drag") {
        parse_numbers(a.args[0] + "," + a.args[1], 2);
        parse_integer(a.args[2], 1, 100000);
      } else if (a.verb == "zoom") {
        parse_numbers(a.args[0], 1);
      } else if (a.verb == "pan") {
        parse_numbers(a.args[0] + "," + a.args[1], 2);
      } else if (a.verb == "mode") {
        parse_enum<DragMode>(a.args[0]);
      } else if (a.verb == "style") {
        parse_enum<Style>(a.args[0]);
      } else if (a.verb == "set" && !find_scene_key(a.args[0])) {
        throw InputError("unknown setting '" + a.args[0] + "'");
      }
    } catch (const InputError& e) {
      throw InputError(where + ": " + a.verb + ": " + e.what());
    }
    actions.push_back(std::move(a));
  }
  return actions;
}

}  // namespace ibfvs::app
