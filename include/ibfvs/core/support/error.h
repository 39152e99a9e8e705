#pragma once
// Exceptions thrown at the library boundary. Every message names the input
// (file, option or value) and the problem, so the CLI can print it as is.

#include <stdexcept>
#include <string>
#include <utility>

namespace ibfvs {

/// A message on one line: line breaks, tabs and other control characters
/// (from a file's bytes or a value quoted in it) become '?'.
inline std::string one_line(std::string text) {
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return text;
}

/// Bad input: a file that cannot be read or parsed, a field with bad values,
/// an impossible parameter. The message names the input and the problem.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A setting with an impossible value. `key()` names the setting as scenes
/// do ("color_range"); front ends show it their own way (the command line as
/// its flag, --color-range), so the library never names a flag.
class SettingError : public InputError {
 public:
  SettingError(std::string key, const std::string& problem)
      : InputError(one_line(key + ": " + problem)),
        key_(one_line(std::move(key))),
        problem_(one_line(problem)) {}
  [[nodiscard]] const std::string& key() const { return key_; }
  [[nodiscard]] const std::string& problem() const { return problem_; }

 private:
  std::string key_, problem_;
};

/// A failure of the graphics system (no context, a shader that does not
/// compile, a GL error reported through KHR_debug).
class GraphicsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ibfvs
