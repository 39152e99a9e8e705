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

/// The inverse: a scene (TOML text) from `ibfvs render` arguments ("--key
/// value", "--key=value" or a bare flag), the last value of an option
/// winning and repeatable ones (element, scalar, field_step) adding up, so
/// that scene_arguments of the result gives the same run. The viewer saves
/// its state with it. Throws InputError for an option scenes do not know.
std::string scene_toml(const std::vector<std::string>& arguments);

}  // namespace ibfvs::app
