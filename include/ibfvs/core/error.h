#pragma once
// Exceptions thrown at the library boundary. Every message names the input
// (file, option or value) and the problem, so the CLI can print it as is.

#include <stdexcept>
#include <string>

namespace ibfvs {

/// Bad input: a file that cannot be read or parsed, a field with bad values,
/// an impossible parameter. The message names the input and the problem.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A failure of the graphics system (no context, a shader that does not
/// compile, a GL error reported through KHR_debug).
class GraphicsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ibfvs
