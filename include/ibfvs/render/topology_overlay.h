#pragma once
// The topology overlay's pass (overlay_geometry.h has what it draws and
// why): the geometry on the GPU, drawn over F with the surface's depth.
#include <cstddef>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "ibfvs/gl/objects.h"
#include "ibfvs/render/overlay_geometry.h"

namespace ibfvs {

/// The pass: the geometry on the GPU, drawn into the framebuffer bound now
/// (F and the surface's depth) with `view` and `projection`.
class TopologyOverlay {
 public:
  TopologyOverlay();
  /// Replaces what is drawn: one step's features, or those between two
  /// steps (topology_morph.h).
  void set(const FlowTopology& topology, glm::ivec2 size);
  void set(const TopologyMorph& morph, glm::ivec2 size);
  [[nodiscard]] bool empty() const { return index_count_ == 0; }
  /// Draws the features `mix` (0 to 1) of the way from the first step to the second.
  void draw(const glm::mat4& view, const glm::mat4& projection, glm::ivec2 size, float mix = 0.0f);

 private:
  gl::Program program_;
  gl::Buffer vertices_, indices_;
  gl::VertexArray vao_;
  std::size_t index_count_ = 0;
  OverlaySizes sizes_;
};

}  // namespace ibfvs
