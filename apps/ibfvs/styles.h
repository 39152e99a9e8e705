#pragma once
// The paper's looks as named styles (section 5: "for standard cases ... we
// have defined default settings"). A style is a list of default options put
// before everything else on the command line, so that a scene or an explicit
// option overrides any of them.

#include <string>
#include <vector>

namespace ibfvs::app {

/// The options of a style. Throws InputError for an unknown name.
std::vector<std::string> style_arguments(const std::string& name);

/// The names, for help and errors.
const char* style_names();

}  // namespace ibfvs::app
