#pragma once
// GLSL sources of the IBFVS pass.

namespace ibfvs::shaders {

extern const char* const kIbfvsVertex;
extern const char* const kIbfvsFragment;

}  // namespace ibfvs::shaders
