// GLSL parts that more than one of the sources in shaders.cpp put together,
// defined in display_shaders.cpp. Internal to the render library.
#pragma once

namespace ibfvs::shaders::parts {

extern const char* const kDisplayFilter;        // the display filter and its taps
extern const char* const kContrast;             // section 3.4's contrast stage
extern const char* const kDisplayFragmentHead;  // the display pass's inputs
extern const char* const kDisplayFragmentMain;  // and its main()

}  // namespace ibfvs::shaders::parts
