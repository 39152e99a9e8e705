#pragma once
// The viewer's scripts (`ibfvs view --script FILE`): timed actions, one per
// line, `FRAME VERB ARGS...`, '#' comments, frames not decreasing. Tests and
// demos drive the real window with them. Every verb is listed once, in the
// table of script_runner.cpp: its arguments, its help, how its arguments are
// checked when the file is read and what it does when its frame comes.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "ibfvs/viewer_session.h"

namespace ibfvs::app {

/// One timed action of a script.
struct ScriptAction {
  int frame = 0;     ///< the frame before which it happens
  std::string verb;  ///< a verb of script_verbs()
  std::vector<std::string> args;
};

/// What only the window can do: the runner asks it.
class WindowActions {
 public:
  virtual ~WindowActions() = default;
  virtual void capture_window(const std::string& file) = 0;  ///< after this frame's panel
  virtual void toggle_help() = 0;
  virtual void quit() = 0;
};

/// Verb names and argument counts, for help and errors.
struct ScriptVerbInfo {
  std::string_view name;
  std::size_t arguments;
  std::string help;
};
std::vector<ScriptVerbInfo> script_verbs();
std::string script_verb_names();  ///< "drag, zoom, ..."

/// Reads and checks a script. Throws InputError naming the file and line.
std::vector<ScriptAction> read_script(const std::filesystem::path& path);

/// Runs a script's actions as their frames come.
class ScriptRunner {
 public:
  explicit ScriptRunner(std::vector<ScriptAction> actions) : actions_(std::move(actions)) {}
  /// Before each frame: continues a scripted drag, then runs every action
  /// due at viewer.frame_count(). Stops after quit. Throws what an action
  /// throws (InputError, SettingError).
  void run(ViewerSession& viewer, WindowActions& window);
  /// A scripted drag is under way (the window's mouse must not end it).
  [[nodiscard]] bool dragging() const { return drag_frames_left_ > 0; }
  [[nodiscard]] bool done() const { return next_ >= actions_.size(); }

  // The verbs' own state: a drag spread over frames.
  void start_drag(glm::vec2 total, int frames);

 private:
  std::vector<ScriptAction> actions_;
  std::size_t next_ = 0;
  glm::vec2 drag_per_frame_{0.0f};
  int drag_frames_left_ = 0;
};

}  // namespace ibfvs::app
