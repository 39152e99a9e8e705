#pragma once
// GLSL sources of the IBFVS pass and of the noise grid pass.

#include <string>

namespace ibfvs::shaders {

extern const char* const kIbfvsVertex;
std::string ibfvs_fragment_source();
extern const char* const kGridVertex;
std::string grid_fragment_source();

}  // namespace ibfvs::shaders
