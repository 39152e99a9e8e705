#pragma once
// GLSL sources of the IBFVS pass.

namespace ibfvs::shaders {

extern const char* const kIbfvsVertex;
extern const char* const kIbfvsFragment;
extern const char* const kGridVertex;
extern const char* const kGridFragment;

}  // namespace ibfvs::shaders
