#pragma once
// GLSL sources of the IBFVS pass, the noise grid pass and the statistics
// pass, from one generator for every place the pass runs: desktop OpenGL 4.5
// and GLSL ES 3.00 (WebGL2).

#include <string>

#include "ibfvs/render/shader_features.h"

namespace ibfvs::shaders {

/// The shading language a source is emitted in. The bodies are the same;
/// only the prelude differs (the version, ES's precisions, and sampler units:
/// declared with layout(binding) in GL 4.5, set by name at run time in ES,
/// to the same numbers).
enum class Dialect { Gl45, Es300 };

std::string ibfvs_vertex_source(const ShaderFeatures& features, Dialect dialect = Dialect::Gl45);
std::string ibfvs_fragment_source(const ShaderFeatures& features, Dialect dialect = Dialect::Gl45);
/// The IBFVS pass split in two (deferred_pass in pass_settings.h): the
/// triangles' half, with ibfvs_vertex_source, writes (t(x), t(x)'s depth,
/// the depth) and (fwidth of the depth, the diffuse term, the scalars); the
/// other, with display_vertex_source over the surface's pixels, reads them
/// and writes what ibfvs_fragment_source writes.
std::string gbuffer_fragment_source(const ShaderFeatures& features,
                                    Dialect dialect = Dialect::Gl45);
std::string resolve_fragment_source(const ShaderFeatures& features,
                                    Dialect dialect = Dialect::Gl45);
/// The display pass, where the features have a tap texture (tap_texture in
/// pass_settings.h): the display filter, the contrast stage and F, once per
/// pixel of the surface, from what the IBFVS pass left.
std::string display_fragment_source(const ShaderFeatures& features,
                                    Dialect dialect = Dialect::Gl45);
/// One triangle that covers the viewport (the grid and statistics passes).
std::string grid_vertex_source(Dialect dialect = Dialect::Gl45);
/// The same on the far plane (the display pass, depth test GREATER).
std::string display_vertex_source(Dialect dialect = Dialect::Gl45);
std::string grid_fragment_source(Dialect dialect = Dialect::Gl45);
/// The statistics pass of the contrast stage (grey F_t in two channels, or colour).
std::string stats_fragment_source(bool mono_texture, Dialect dialect = Dialect::Gl45);
/// Copies F and the surface's depth into a host's framebuffer (ParaView's),
/// the background left as the host drew it; with u_interior 1 not at the
/// surface's silhouettes (src/render/glsl/host_fragment.glsl).
std::string host_fragment_source();
/// The topology overlay (src/render/glsl/overlay_*.glsl; topology_overlay.h).
std::string overlay_vertex_source(Dialect dialect = Dialect::Gl45);
std::string overlay_fragment_source(Dialect dialect = Dialect::Gl45);

}  // namespace ibfvs::shaders
