#pragma once
// Scene files: a TOML file that describes a whole `ibfvs render` run. Every
// key is a render option (underscores for dashes); docs/scenes.md lists them.

#include <filesystem>
#include <string>
#include <vector>

namespace ibfvs::app {

/// True for a path ending in .toml.
bool is_scene_path(const std::string& arg);

/// Reads a scene and returns the equivalent `ibfvs render` arguments, to be
/// placed before the command line's own (which then override them). "${data}"
/// in a string is the fetched-data folder. Throws InputError "FILE:LINE: ..."
/// for a syntax error, an unknown key or a value of the wrong type.
std::vector<std::string> scene_arguments(const std::filesystem::path& path);

}  // namespace ibfvs::app
