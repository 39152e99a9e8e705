#include "ibfvs/render/topology_overlay.h"

#include <cstddef>
#include <span>

#include "ibfvs/render/shaders.h"

namespace ibfvs {

TopologyOverlay::TopologyOverlay()
    : program_(shaders::overlay_vertex_source(), shaders::overlay_fragment_source()),
      vao_(gl::VertexArray::create()) {}

void TopologyOverlay::set(const FlowTopology& topology, glm::ivec2 size) {
  set(hold(topology), size);
}

void TopologyOverlay::set(const TopologyMorph& morph, glm::ivec2 size) {
  const OverlayGeometry g = build_overlay(morph, size);
  sizes_ = overlay_sizes(size.y);
  index_count_ = g.indices.size();
  if (g.indices.empty()) return;
  vertices_ = gl::Buffer(std::as_bytes(std::span(g.vertices)));
  indices_ = gl::Buffer(std::as_bytes(std::span(g.indices)));
  vao_ = gl::VertexArray::create();
  // One binding per attribute: a binding's offset is the attribute's.
  constexpr std::size_t stride = sizeof(OverlayVertex);
  vao_.attribute(0, vertices_, 0, 3, offsetof(OverlayVertex, point), stride);
  vao_.attribute(1, vertices_, 1, 3, offsetof(OverlayVertex, other), stride);
  vao_.attribute(2, vertices_, 2, 2, offsetof(OverlayVertex, corner), stride);
  vao_.attribute(3, vertices_, 3, 3, offsetof(OverlayVertex, colour), stride);
  vao_.attribute(4, vertices_, 4, 1, offsetof(OverlayVertex, shape), stride);
  vao_.attribute(5, vertices_, 5, 3, offsetof(OverlayVertex, point_to), stride);
  vao_.attribute(6, vertices_, 6, 3, offsetof(OverlayVertex, other_to), stride);
  vao_.attribute(7, vertices_, 7, 3, offsetof(OverlayVertex, point_bulge), stride);
  vao_.attribute(8, vertices_, 8, 3, offsetof(OverlayVertex, other_bulge), stride);
  vao_.attribute(9, vertices_, 9, 1, offsetof(OverlayVertex, span), stride);
  vao_.index_buffer(indices_);
}

void TopologyOverlay::draw(const glm::mat4& view, const glm::mat4& projection, glm::ivec2 size,
                           float mix) {
  if (index_count_ == 0) return;
  program_.use();
  program_.set(program_.location("u_view"), view);
  program_.set(program_.location("u_projection"), projection);
  program_.set(program_.location("u_viewport"), glm::vec2(size));
  program_.set(program_.location("u_line_width"), sizes_.line_width);
  program_.set(program_.location("u_glyph"), sizes_.glyph);
  program_.set(program_.location("u_lift"), kOverlayLift);
  program_.set(program_.location("u_mix"), mix);
  gl::draw_over(true);
  vao_.bind();
  gl::draw_triangles(index_count_, true);
  gl::draw_over(false);
}

}  // namespace ibfvs
