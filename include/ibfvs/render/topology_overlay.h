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
  /// Replaces what is drawn.
  void set(const FlowTopology& topology, glm::ivec2 size);
  [[nodiscard]] bool empty() const { return index_count_ == 0; }
  void draw(const glm::mat4& view, const glm::mat4& projection, glm::ivec2 size);

 private:
  gl::Program program_;
  gl::Buffer vertices_, indices_;
  gl::VertexArray vao_;
  std::size_t index_count_ = 0;
  OverlaySizes sizes_;
};

}  // namespace ibfvs
