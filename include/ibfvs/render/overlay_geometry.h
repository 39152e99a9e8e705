#pragma once
// The topology overlay's geometry (issue 64, `overlay = topology`), without
// GL: what TopologyOverlay (topology_overlay.h) draws and the page's runtime
// draws alike. A field's critical
// points as glyphs by kind, its separation and attachment lines in the
// kinds' colours (kind_styles, the one table), and a legend, drawn over
// the frame's picture F where the surface does not hide them (its depth).
//
// Lines and glyphs are quads extruded in the image (widths in pixels,
// whatever the distance), lifted towards the eye by a small fraction of
// their distance so that the surface they lie on does not hide them; the
// legend's text is stb_easy_font's bitmap font. build_overlay makes the
// quads on the CPU; overlay_reference is the CPU reference of what the
// pass draws (tests compare the two).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibfvs/core/fields/topology.h"
#include "ibfvs/core/fields/topology_morph.h"
#include "ibfvs/core/image/image.h"

namespace ibfvs {

/// One corner of a quad of the overlay (see overlay_vertex.glsl).
struct OverlayVertex {
  glm::vec3 point{0.0f};   ///< this end of a segment, a glyph's centre, or pixels (legend)
  glm::vec3 other{0.0f};   ///< a segment's other end
  glm::vec2 corner{0.0f};  ///< segment: (cap, side); glyph and legend: the corner, -1..1
  glm::vec3 colour{0.0f};
  float shape = 0.0f;           ///< kOverlay* below
  glm::vec3 point_to{0.0f};     ///< `point` at the next step (topology_morph.h)
  glm::vec3 other_to{0.0f};     ///< `other` at the next step
  glm::vec3 point_bulge{0.0f};  ///< `point`'s offset from its chord halfway (FeatureMorph)
  glm::vec3 other_bulge{0.0f};  ///< `other`'s
  float span = 0.0f;            ///< MorphSpan: when in the step it is drawn
};
/// Floats a corner (the page's vertex codec takes them so).
inline constexpr std::size_t kOverlayFloats = sizeof(OverlayVertex) / sizeof(float);
static_assert(kOverlayFloats == 25, "the page's runtime reads 25 floats a corner");

// The shapes (overlay_vertex.glsl has the same numbers).
inline constexpr float kOverlayLine = 0.0f;         ///< a segment of a line
inline constexpr float kOverlayPixels = 7.0f;       ///< a legend rectangle, in pixels
inline constexpr float kOverlayLegendKind = 10.0f;  ///< + kind 1-6: a legend's glyph, in pixels

/// Sizes in pixels for an image of `height` rows.
struct OverlaySizes {
  float line_width = 3.0f;
  float glyph = 11.0f;
  int text_scale = 1;  ///< stb_easy_font's 6-pixel letters, times this
};
OverlaySizes overlay_sizes(int height);

/// The lift towards the eye: the fraction of a point's eye distance.
inline constexpr float kOverlayLift = 0.004f;

struct OverlayGeometry {
  std::vector<OverlayVertex> vertices;
  std::vector<std::uint32_t> indices;  ///< two triangles a quad
};

/// The quads of `morph` for an image of `size`: a segment per line piece, a
/// glyph per critical point, each moving from its place at one step to its
/// place at the next as the pass's `u_mix` goes from 0 to 1, and the legend
/// (bottom left: a swatch and "kind (count)" for each kind present; the
/// second step's counts from halfway).
OverlayGeometry build_overlay(const TopologyMorph& morph, glm::ivec2 size);
/// One step's, held still.
OverlayGeometry build_overlay(const FlowTopology& topology, glm::ivec2 size);

/// The CPU reference (of the pass at `mix`: of topology_at(morph, mix)): per pixel (rows
/// bottom-up), the kind drawn there (0: none) by a point-sampled rasterisation of the same lifted
/// segments and glyph discs, tested against `depth` (the frame's window depth, 1 off the surface)
/// as the pass tests it. Without the legend.
std::vector<int> overlay_reference(const FlowTopology& topology, const glm::mat4& view,
                                   const glm::mat4& projection, glm::ivec2 size,
                                   const ImageF& depth);

}  // namespace ibfvs
