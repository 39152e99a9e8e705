// The GLSL snippets of src/render/glsl/, one constant per file, embedded at
// build time (cmake/embed_glsl.cmake). Each snippet is self-contained (its
// #if blocks close in it); shaders.cpp puts them together for each pass and
// dialect. Internal to the render library.
#pragma once

namespace ibfvs::shaders::glsl {

extern const char* const ibfvs_vertex;
extern const char* const fullscreen_vertex;
extern const char* const noise_profile;
extern const char* const ibfvs_fragment_inputs;
extern const char* const gbuffer_main;
extern const char* const ibfvs_fragment_outputs;
extern const char* const ibfvs_fragment_main;
extern const char* const grid_fragment;
extern const char* const stats_fragment;
extern const char* const display_filter;
extern const char* const contrast;
extern const char* const display_fragment_inputs;
extern const char* const display_fragment_main;
extern const char* const host_fragment;
extern const char* const overlay_vertex;
extern const char* const overlay_fragment;

}  // namespace ibfvs::shaders::glsl
