#include "ibfvs/script_runner.h"

#include <fstream>
#include <sstream>

#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs::app {
namespace {

using Args = std::vector<std::string>;

float number(const std::string& text) {
  return parse_numbers(text, 1)[0];
}

// The size of a snapshot, "W,H".
glm::ivec2 snapshot_size(const std::string& text) {
  const std::vector<float> n = parse_numbers(text, 2, "W,H");
  if (!(n[0] >= 1 && n[1] >= 1 && n[0] <= 16384 && n[1] <= 16384) || n[0] != std::floor(n[0]) ||
      n[1] != std::floor(n[1]))
    throw InputError("the size must be whole numbers within 1..16384, got '" + text + "'");
  return {static_cast<int>(n[0]), static_cast<int>(n[1])};
}

struct Context {
  ViewerSession& viewer;
  WindowActions& window;
  ScriptRunner& runner;
};

struct Verb {
  std::string_view name;
  std::size_t arguments;
  std::string help;
  void (*check)(const Args&);  ///< when reading: throws InputError for bad arguments
  void (*run)(Context&, const Args&);
};

void no_check(const Args&) {}

const std::vector<Verb>& verbs() {
  static const std::vector<Verb> table = {
      {"drag", 3, "DX DY FRAMES: a mouse drag spread over FRAMES frames, through the drag mode",
       [](const Args& a) {
         parse_numbers(a[0] + "," + a[1], 2);
         parse_integer(a[2], 1, 100000);
       },
       [](Context& c, const Args& a) {
         c.viewer.begin_drag();
         c.runner.start_drag({number(a[0]), number(a[1])},
                             static_cast<int>(parse_integer(a[2], 1, 100000)));
       }},
      {"zoom", 1, "STEPS: mouse-wheel steps", [](const Args& a) { number(a[0]); },
       [](Context& c, const Args& a) { c.viewer.zoom(number(a[0])); }},
      {"pan", 2, "DX DY: pan by pixels", [](const Args& a) { parse_numbers(a[0] + "," + a[1], 2); },
       [](Context& c, const Args& a) {
         c.viewer.pan({number(a[0]), number(a[1])});
       }},
      {"set", 2, "KEY VALUE: any scene key (alpha, step, color_map, mesh, ...)",
       [](const Args& a) {
         if (!find_scene_key(a[0])) throw InputError("unknown setting '" + a[0] + "'");
       },
       [](Context& c, const Args& a) { c.viewer.set(a[0], a[1]); }},
      {"mode", 1, "the drag mode: " + enum_name_list<DragMode>(),
       [](const Args& a) { parse_enum<DragMode>(a[0]); },
       [](Context& c, const Args& a) { c.viewer.drag_mode = parse_enum<DragMode>(a[0]); }},
      {"lock", 0, "lock the texture (3.7)", no_check,
       [](Context& c, const Args&) { c.viewer.session().lock(); }},
      {"unlock", 0, "resume the animation", no_check,
       [](Context& c, const Args&) { c.viewer.session().unlock(); }},
      {"screenshot", 1, "FILE.png: the image", no_check,
       [](Context& c, const Args& a) { c.viewer.screenshot(a[0]); }},
      {"window", 1, "FILE.png: the window with the panel", no_check,
       [](Context& c, const Args& a) { c.window.capture_window(a[0]); }},
      {"texture", 1, "FILE.png: F_t, 16 bits", no_check,
       [](Context& c, const Args& a) { c.viewer.write_texture(a[0]); }},
      {"save", 1, "SCENE.toml: the current state as a scene", no_check,
       [](Context& c, const Args& a) { c.viewer.save_scene(a[0]); }},
      {"style", 1, "a style: " + enum_name_list<Style>(),
       [](const Args& a) { parse_enum<Style>(a[0]); },
       [](Context& c, const Args& a) { c.viewer.apply_style(parse_enum<Style>(a[0])); }},
      {"load", 1, "MESH or SCENE.toml", no_check,
       [](Context& c, const Args& a) { c.viewer.load(a[0]); }},
      {"element", 1, "AX,AY,AZ,BX,BY,BZ,ROT,RAD,TAN[,CORE]: add a flow element",
       [](const Args& a) { FlowElement::parse(a[0]); },
       [](Context& c, const Args& a) { c.viewer.add_element(FlowElement::parse(a[0])); }},
      {"record", 0, "start or stop recording an MP4", no_check,
       [](Context& c, const Args&) { c.viewer.toggle_recording(); }},
      {"snapshot", 2, "W,H FILE.png: the current state rendered offscreen at that size",
       [](const Args& a) { snapshot_size(a[0]); },
       [](Context& c, const Args& a) {
         const glm::ivec2 size = snapshot_size(a[0]);
         c.viewer.snapshot(size.x, size.y, a[1]);
       }},
      {"help", 0, "show or hide the help", no_check,
       [](Context& c, const Args&) { c.window.toggle_help(); }},
      {"quit", 0, "close the window", no_check, [](Context& c, const Args&) { c.window.quit(); }},
  };
  return table;
}

const Verb* find_verb(std::string_view name) {
  for (const Verb& v : verbs())
    if (v.name == name) return &v;
  return nullptr;
}

}  // namespace

std::vector<ScriptVerbInfo> script_verbs() {
  std::vector<ScriptVerbInfo> out;
  for (const Verb& v : verbs()) out.push_back({v.name, v.arguments, v.help});
  return out;
}

std::string script_verb_names() {
  std::string out;
  for (const Verb& v : verbs()) {
    if (!out.empty()) out += ", ";
    out += v.name;
  }
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
    const Verb* verb = find_verb(a.verb);
    if (!verb)
      throw InputError(where + ": unknown action '" + a.verb + "' (" + script_verb_names() + ")");
    for (std::string w; words >> w;) a.args.push_back(w);
    if (a.args.size() != verb->arguments)
      throw InputError(where + ": '" + a.verb + "' takes " + std::to_string(verb->arguments) +
                       " argument(s), got " + std::to_string(a.args.size()));
    if (!actions.empty() && a.frame < actions.back().frame)
      throw InputError(where + ": frames must not decrease");
    try {
      verb->check(a.args);
    } catch (const InputError& e) {
      throw InputError(where + ": " + a.verb + ": " + e.what());
    }
    actions.push_back(std::move(a));
  }
  return actions;
}

void ScriptRunner::start_drag(glm::vec2 total, int frames) {
  drag_frames_left_ = frames;
  drag_per_frame_ = total / static_cast<float>(frames);
}

void ScriptRunner::run(ViewerSession& viewer, WindowActions& window) {
  if (drag_frames_left_ > 0) {
    viewer.drag_by(drag_per_frame_, false);
    if (--drag_frames_left_ == 0) viewer.end_drag();
  }
  Context context{viewer, window, *this};
  while (next_ < actions_.size() && actions_[next_].frame <= viewer.frame_count()) {
    const ScriptAction& a = actions_[next_++];
    find_verb(a.verb)->run(context, a.args);
    if (a.verb == "quit") {
      next_ = actions_.size();
      return;
    }
  }
}

}  // namespace ibfvs::app
