#pragma once
// Small helpers on file names shared by the readers, writers and commands.

#include <filesystem>
#include <string>

namespace ibfvs {

/// The extension with its dot, in lower case: "Cow.OFF" -> ".off", "x" -> "".
std::string lower_extension(const std::filesystem::path& path);

}  // namespace ibfvs
