#pragma once
// The viewer's Dear ImGui panel: a side bar beside the image with the live
// texture settings, the drag mode, lock and pause, and sections for more
// parameters, styles and files, flow elements, saving and recording. It
// only reads and calls the ViewerSession; its lists come from the enum
// name tables.

#include <string>

#include "ibfvs/viewer_session.h"

namespace ibfvs::app {

class ViewerPanel {
 public:
  static constexpr int kWidth = 250;  ///< in window units; the window is this much wider

  /// Draws the panel for this frame (between ImGui::NewFrame and Render).
  /// `show` is cleared by its close button, `show_help` toggled by its help
  /// button; `fps` goes in its title.
  void draw(ViewerSession& viewer, bool& show, bool& show_help, double fps);

 private:
  void draw_more_parameters(ViewerSession& viewer);
  void draw_styles_and_files(ViewerSession& viewer);
  void draw_elements(ViewerSession& viewer);
  void draw_save_and_record(ViewerSession& viewer);

  std::string save_path_ = "view.toml";
  std::string load_path_;
  int snapshot_size_[2] = {2048, 2048};
};

}  // namespace ibfvs::app
