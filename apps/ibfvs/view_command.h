#pragma once
// `ibfvs view`: the interactive window (GLFW + Dear ImGui) on the same engine
// and the same options as `ibfvs render`.

#include <string>
#include <vector>

#include "ibfvs/render_command.h"

namespace CLI {
class App;
}

namespace ibfvs::app {

struct ViewOptions {
  SceneOptions scene;             ///< mesh, field, texture, colour, camera: as for render
  std::string drag = "previous";  ///< what the texture does while dragging (DragMode)
  bool vsync = false;             ///< wait for the display's refresh
  bool no_panel = false;          ///< hide the ImGui panel (and the help) at the start
  std::string script;             ///< timed actions (viewer_state.h), for tests and demos
};

/// Registers the view subcommand's options: every render option plus its own.
void add_view_options(CLI::App& command, ViewOptions& options);

/// Opens the window and runs until it is closed (or the script quits).
/// Returns the exit status. Without a display it throws InputError saying so.
int run_view(const ViewOptions& options);

}  // namespace ibfvs::app
