// The passes' GLSL, one generator for desktop GL and WebGL2: the snippets
// of src/render/glsl/ (glsl_sources.h), put together for each pass, with
// the features' defines and each dialect's prelude.
#include "ibfvs/render/shaders.h"

#include <string>

#include "glsl_sources.h"
#include "ibfvs/core/texture/display.h"
#include "ibfvs/render/texture_units.h"

namespace ibfvs::shaders {

namespace {

// What differs between the dialects, in this one place: the version line,
// WebGL2's required precisions, and sampler units, which GLSL ES 3.00 cannot
// declare in the shader (layout(binding) is ES 3.10): an ES runtime sets
// them by name (glUniform1i) to the numbers the UNIT_ defines give here.
std::string prelude(Dialect dialect) {
  std::string text =
      dialect == Dialect::Es300
          ? "#version 300 es\n"
            "precision highp float;\nprecision highp int;\nprecision highp sampler2D;\n"
            "#define BINDING(n)\n"
          : "#version 450 core\n#define BINDING(n) layout(binding = n)\n";
  // Every sampler's unit by name (texture_units.h): BINDING(UNIT_PREVIOUS).
  for (const units::NamedUnit& u : units::kAll)
    text += std::string("#define UNIT_") + u.name + " " + std::to_string(u.unit) + "\n";
  return text;
}

std::string with_defines(const ShaderFeatures& features, const std::string& body, bool profile,
                         Dialect dialect) {
  std::string source = prelude(dialect);
  const auto define = [&](bool on, const char* name) {
    if (on) source += std::string("#define ") + name + "\n";
  };
  for (const FeatureFlag& flag : kFlags) define(features.*flag.member, flag.define);
  if (features.filter_taps > 0)
    source += "#define IBFVS_FILTER " + std::to_string(features.filter_taps) + "\n";
  define(tap_texture(features), "IBFVS_TAP_TEXTURE");
  if (features.sharpen || features.compensate)
    source += "#define IBFVS_SHARPEN_REACH " + std::to_string(ibfvs::kSharpenReach) + "\n";
  // The display's work that follows the streaks' direction (the flow's own).
  define(features.sharpen || features.compensate || features.filter_taps > 0, "IBFVS_STREAKS");
  if (profile) source += glsl::noise_profile;
  return source + body;
}

}  // namespace

std::string host_fragment_source() {
  return prelude(Dialect::Gl45) + glsl::host_fragment;
}

std::string overlay_vertex_source(Dialect dialect) {
  return prelude(dialect) + glsl::overlay_vertex;
}

std::string overlay_fragment_source(Dialect dialect) {
  return prelude(dialect) + glsl::overlay_fragment;
}

namespace {

// The IBFVS pass's fragment shader after its contrast stage (also the
// deferred pass's second half, with IBFVS_RESOLVE).
std::string ibfvs_fragment_body() {
  return std::string(glsl::ibfvs_fragment_inputs) + glsl::ibfvs_fragment_outputs +
         glsl::display_filter + glsl::ibfvs_fragment_main;
}

}  // namespace

std::string ibfvs_vertex_source(const ShaderFeatures& features, Dialect dialect) {
  return with_defines(features, std::string(glsl::contrast) + glsl::ibfvs_vertex, false, dialect);
}

std::string ibfvs_fragment_source(const ShaderFeatures& features, Dialect dialect) {
  return with_defines(features, std::string(glsl::contrast) + ibfvs_fragment_body(),
                      features.object_noise, dialect);
}

std::string gbuffer_fragment_source(const ShaderFeatures& features, Dialect dialect) {
  return with_defines(
      features,
      std::string("#define IBFVS_GBUFFER\n") + glsl::ibfvs_fragment_inputs + glsl::gbuffer_main,
      false, dialect);
}

std::string resolve_fragment_source(const ShaderFeatures& features, Dialect dialect) {
  return with_defines(
      features, std::string("#define IBFVS_RESOLVE\n") + glsl::contrast + ibfvs_fragment_body(),
      features.object_noise, dialect);
}

std::string display_fragment_source(const ShaderFeatures& features, Dialect dialect) {
  return with_defines(features,
                      std::string(glsl::contrast) + glsl::display_fragment_inputs +
                          glsl::display_filter + glsl::display_fragment_main,
                      false, dialect);
}

std::string grid_vertex_source(Dialect dialect) {
  return prelude(dialect) + glsl::fullscreen_vertex;
}

std::string display_vertex_source(Dialect dialect) {
  return prelude(dialect) + "#define IBFVS_FAR\n" + glsl::fullscreen_vertex;
}

std::string stats_fragment_source(bool mono_texture, Dialect dialect) {
  return prelude(dialect) + (mono_texture ? "#define IBFVS_MONO_TEXTURE\n" : "") +
         glsl::stats_fragment;
}

std::string grid_fragment_source(Dialect dialect) {
  return prelude(dialect) + glsl::noise_profile + glsl::grid_fragment;
}

}  // namespace ibfvs::shaders
