#pragma once
// `ibfvs render`: headless IBFVS rendering to PNG or video, and the command
// line's edge shared with `ibfvs view`: every scene key as a flag
// (--color-range for color_range), a scene file or mesh as the positional
// argument, parsed once into a typed Scene.

#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "ibfvs/core/scene/scene.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace ibfvs::app {

/// The flags of every scene key, as given on the command line.
struct SceneOptions {
  std::string input;  ///< SCENE.toml or a mesh (positional)
  std::vector<std::pair<const SceneKey*, CLI::Option*>> flags;
};

/// Registers the positional input and one flag per scene key on `command`.
void add_scene_options(CLI::App& command, SceneOptions& options);

/// The scene the command line describes: the scene file's settings, then the
/// flags (a style, from either, first). Throws SettingError / InputError.
Scene scene_from_command_line(const SceneOptions& options);

/// The command line's flag for a scene key: color_range -> --color-range.
std::string flag_of(std::string_view key);

/// Throws InputError "OPTION: ..." when `out` is a folder or its folder
/// does not exist (every command that writes a file).
void ensure_parent(const std::filesystem::path& out, const char* option);

/// One line for an error: a SettingError names the flag, others as they are.
std::string error_line(const std::exception& error);

/// Every scene key: name, TOML type, flag, default and meaning, as text, or
/// as the Markdown table of docs/scenes.md (`ibfvs keys --markdown`).
std::string scene_keys_table(bool markdown);

/// Renders; returns the exit status. Throws InputError / SettingError /
/// GraphicsError.
/// `scene_file`: the scene file it came from, if any (an output must not
/// overwrite it). Ctrl-C or SIGTERM stops it after the frame under way: a
/// video is finished with the frames so far and the status is 128 + signal.
int run_render(const Scene& scene, const std::string& scene_file = {});

}  // namespace ibfvs::app
