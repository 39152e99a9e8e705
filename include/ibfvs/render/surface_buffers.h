#pragma once
// The surface the IBFVS pass draws, on the GPU: its points and normals (at
// two time steps where it moves, with each vertex's screw between them),
// the pair of steps the last frame drew (its advection's source), the
// field at two time steps, the per-vertex scalars, the triangles, and the
// vertex array that reads them at the IBFVS vertex shader's attributes.
// IbfvsRenderer owns one; it needs a current OpenGL 4.5 context.

#include <cstddef>
#include <span>

#include <glm/vec3.hpp>

#include "ibfvs/core/geometry/rigid_motion.h"
#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/gl/objects.h"

namespace ibfvs {

class SurfaceBuffers {
 public:
  /// A new surface and its field (one vector per vertex), standing still.
  /// Throws InputError for a mesh without normals or a field of another size.
  void upload(const TriMesh& mesh, std::span<const glm::vec3> field);
  /// The surface moves: its points and normals at this step and the next,
  /// and each vertex's screw between them (empty: along chords). With
  /// `keep_drawn`, the pair the last frame drew stays the next frame's
  /// advection source (unless one is kept already: two changes between
  /// frames). Throws InputError for a size that is not the vertex count.
  void set_steps(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                 std::span<const glm::vec3> next_positions, std::span<const glm::vec3> next_normals,
                 const SurfaceMotion& motion, bool keep_drawn);
  /// The same vertices with other triangles (each index below the vertex
  /// count, else InputError): points, fields, the pair the last frame drew
  /// and whether it drew this surface all stay.
  void set_triangles(std::span<const Triangle> triangles);
  /// Points the drawn attributes (7, 8, 11, 12) at the pair the last frame
  /// drew where its motion enters the advection (`compensate`), else at the
  /// current pair (a vertex taken where it is drawn).
  void point_drawn(bool compensate);
  /// A frame drew the surface at `mix` (not locked): this pair is the one
  /// the next frame's texture comes from.
  void frame_drawn(float mix);

  void set_field(std::span<const glm::vec3> field);
  void set_field_steps(std::span<const glm::vec3> current, std::span<const glm::vec3> next);
  /// Per-vertex (colour, beta) scalars; either may be empty (zeros).
  void set_scalars(std::span<const float> color, std::span<const float> beta);

  void draw();
  [[nodiscard]] std::size_t vertex_count() const { return vertex_count_; }
  [[nodiscard]] bool empty() const { return index_count_ == 0; }
  /// The box of the surface, and of its way between two steps where it moves.
  [[nodiscard]] const Bounds& bounds() const { return bounds_; }
  /// Whether set_steps made it move (until the next upload).
  [[nodiscard]] bool moving() const { return moving_; }
  /// Whether the last frame drew this surface (not one an upload replaced).
  [[nodiscard]] bool drawn_this_mesh() const { return drawn_this_mesh_; }
  /// The mix of the steps the last frame drew.
  [[nodiscard]] float drawn_mix() const { return drawn_mix_; }

 private:
  gl::Buffer vertices_;       // positions and normals interleaved, at this step
  gl::Buffer vertices_next_;  // and at the next, where the surface moves
  gl::Buffer motion_;         // each vertex's screw (omega, lever interleaved; zeros: chords)
  bool moving_ = false;
  // The pair of steps the last frame drew, where set_steps replaced it since
  // (drawn_next_ empty: the one static buffer), its screws and its mix.
  gl::Buffer drawn_;
  gl::Buffer drawn_next_;
  gl::Buffer drawn_motion_;
  bool drawn_elsewhere_ = false;
  float drawn_mix_ = 0.0f;
  bool drawn_this_mesh_ = false;
  gl::Buffer field_;
  gl::Buffer field_next_;
  gl::Buffer scalars_;  // (colour, beta) per vertex
  gl::Buffer indices_;
  gl::VertexArray vao_;
  std::size_t index_count_ = 0;
  std::size_t vertex_count_ = 0;
  Bounds bounds_;
};

}  // namespace ibfvs
