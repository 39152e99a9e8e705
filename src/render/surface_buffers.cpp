// The surface on the GPU (surface_buffers.h).
#include "ibfvs/render/surface_buffers.h"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

template <class T>
std::span<const std::byte> bytes_of(std::span<const T> v) {
  return std::as_bytes(v);
}

// Positions and normals interleaved, as the vertex array reads them.
std::vector<float> interleave(std::span<const glm::vec3> positions,
                              std::span<const glm::vec3> normals) {
  std::vector<float> out;
  out.reserve(positions.size() * 6);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3& p = positions[i];
    const glm::vec3& n = normals[i];
    out.insert(out.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
  }
  return out;
}

// A pair of steps without screws: every vertex along its chord.
gl::Buffer still_motion(std::size_t vertices) {
  const std::vector<float> zeros(vertices * 6, 0.0f);
  return gl::Buffer(bytes_of(std::span<const float>(zeros)));
}

}  // namespace

void SurfaceBuffers::upload(const TriMesh& mesh, std::span<const glm::vec3> field) {
  validate_mesh(mesh, "mesh");
  if (mesh.normals.size() != mesh.positions.size())
    throw InputError("renderer: the mesh needs vertex normals");
  if (field.size() != mesh.positions.size())
    throw InputError("renderer: the field needs one vector per vertex");
  // Interleaved position + normal; the field in its own buffer so that an
  // unsteady field can be replaced without touching the geometry.
  const std::vector<float> interleaved = interleave(mesh.positions, mesh.normals);
  vertices_ = gl::Buffer(bytes_of(std::span<const float>(interleaved)));
  vertices_next_ = gl::Buffer();
  motion_ = gl::Buffer();
  drawn_ = gl::Buffer();
  drawn_next_ = gl::Buffer();
  drawn_motion_ = gl::Buffer();
  moving_ = drawn_elsewhere_ = drawn_this_mesh_ = false;
  field_ = gl::Buffer(bytes_of(field), true);
  field_next_ = gl::Buffer(bytes_of(field), true);
  const std::vector<glm::vec2> zeros(mesh.positions.size(), glm::vec2(0.0f));
  scalars_ = gl::Buffer(bytes_of(std::span<const glm::vec2>(zeros)), true);
  indices_ = gl::Buffer(bytes_of(std::span<const Triangle>(mesh.triangles)));
  vao_ = gl::VertexArray::create();
  vao_.attribute(0, vertices_, 0, 3, 0, 6 * sizeof(float));
  vao_.attribute(1, vertices_, 1, 3, 3 * sizeof(float), 6 * sizeof(float));
  vao_.attribute(2, field_, 2, 3, 0, sizeof(glm::vec3));
  vao_.attribute(4, field_next_, 4, 3, 0, sizeof(glm::vec3));
  vao_.attribute(3, scalars_, 3, 2, 0, sizeof(glm::vec2));
  vao_.index_buffer(indices_);
  index_count_ = mesh.triangles.size() * 3;
  vertex_count_ = mesh.positions.size();
  bounds_ = mesh_bounds(mesh);
}

void SurfaceBuffers::set_steps(std::span<const glm::vec3> positions,
                               std::span<const glm::vec3> normals,
                               std::span<const glm::vec3> next_positions,
                               std::span<const glm::vec3> next_normals, const SurfaceMotion& motion,
                               bool keep_drawn) {
  for (const std::size_t n :
       {positions.size(), normals.size(), next_positions.size(), next_normals.size()})
    if (n != vertex_count_)
      throw InputError("renderer: each surface step needs one position and normal per vertex");
  if (!motion.empty() &&
      (motion.omega.size() != vertex_count_ || motion.lever.size() != vertex_count_))
    throw InputError("renderer: the surface's motion needs one screw per vertex");
  // The pair the last frame drew stays for the next frame's advection, unless
  // it is kept already (two changes without a frame between them). The one
  // static buffer did not move: no screws.
  if (keep_drawn && drawn_this_mesh_ && !drawn_elsewhere_) {
    drawn_ = std::move(vertices_);
    drawn_next_ = moving_ ? std::move(vertices_next_) : gl::Buffer();
    drawn_motion_ = moving_ ? std::move(motion_) : still_motion(vertex_count_);
    drawn_elsewhere_ = true;
  }
  const std::vector<float> a = interleave(positions, normals);
  const std::vector<float> b = interleave(next_positions, next_normals);
  vertices_ = gl::Buffer(bytes_of(std::span<const float>(a)));
  vertices_next_ = gl::Buffer(bytes_of(std::span<const float>(b)));
  motion_ =
      motion.empty()
          ? still_motion(vertex_count_)
          : gl::Buffer(bytes_of(std::span<const float>(interleave(motion.omega, motion.lever))));
  moving_ = true;
  constexpr std::size_t stride = 6 * sizeof(float);
  vao_.attribute(0, vertices_, 0, 3, 0, stride);
  vao_.attribute(1, vertices_, 1, 3, 3 * sizeof(float), stride);
  vao_.attribute(5, vertices_next_, 5, 3, 0, stride);
  vao_.attribute(6, vertices_next_, 6, 3, 3 * sizeof(float), stride);
  vao_.attribute(9, motion_, 9, 3, 0, stride);
  vao_.attribute(10, motion_, 10, 3, 3 * sizeof(float), stride);
  // The box of both steps and of the way between them (a turn leaves the
  // box of its ends): the pixels the surface can cover between them.
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  const auto take = [&](std::span<const glm::vec3> step) {
    for (const glm::vec3& p : step) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  };
  take(positions);
  take(next_positions);
  if (!motion.empty())
    for (const float m : {0.25f, 0.5f, 0.75f})
      take(surface_at(positions, next_positions, motion, m));
  if (!positions.empty()) {
    bounds_.min = lo;
    bounds_.max = hi;
    bounds_.radius = 0.0f;
  }
}

void SurfaceBuffers::set_triangles(std::span<const Triangle> triangles) {
  for (const Triangle& t : triangles)
    for (const std::uint32_t i : t)
      if (i >= vertex_count_)
        throw InputError("renderer: a triangle refers to vertex " + std::to_string(i) + " of " +
                         std::to_string(vertex_count_));
  indices_ = gl::Buffer(bytes_of(triangles));
  vao_.index_buffer(indices_);
  index_count_ = triangles.size() * 3;
}

void SurfaceBuffers::point_drawn(bool compensate) {
  constexpr std::size_t stride = 6 * sizeof(float);
  const bool elsewhere = compensate && drawn_elsewhere_;
  const gl::Buffer& a = elsewhere ? drawn_ : vertices_;
  const gl::Buffer& b = elsewhere ? (drawn_next_ ? drawn_next_ : drawn_) : vertices_next_;
  const gl::Buffer& screws = elsewhere ? drawn_motion_ : motion_;
  vao_.attribute(7, a, 7, 3, 0, stride);
  vao_.attribute(8, b, 8, 3, 0, stride);
  vao_.attribute(11, screws, 11, 3, 0, stride);
  vao_.attribute(12, screws, 12, 3, 3 * sizeof(float), stride);
}

void SurfaceBuffers::frame_drawn(float mix) {
  drawn_ = gl::Buffer();
  drawn_next_ = gl::Buffer();
  drawn_motion_ = gl::Buffer();
  drawn_elsewhere_ = false;
  drawn_mix_ = mix;
  drawn_this_mesh_ = true;
}

void SurfaceBuffers::draw() {
  vao_.bind();
  gl::draw_triangles(index_count_, true);
}

void SurfaceBuffers::set_field(std::span<const glm::vec3> field) {
  if (field.size() != vertex_count_)
    throw InputError("renderer: the field needs one vector per vertex");
  field_.update(0, bytes_of(field));
  field_next_.update(0, bytes_of(field));
}

void SurfaceBuffers::set_field_steps(std::span<const glm::vec3> current,
                                     std::span<const glm::vec3> next) {
  if (current.size() != vertex_count_ || next.size() != vertex_count_)
    throw InputError("renderer: each field step needs one vector per vertex");
  field_.update(0, bytes_of(current));
  field_next_.update(0, bytes_of(next));
}

void SurfaceBuffers::set_scalars(std::span<const float> color, std::span<const float> beta) {
  if ((!color.empty() && color.size() != vertex_count_) ||
      (!beta.empty() && beta.size() != vertex_count_))
    throw InputError("renderer: scalars need one value per vertex");
  std::vector<glm::vec2> packed(vertex_count_, glm::vec2(0.0f));
  for (std::size_t i = 0; i < vertex_count_; ++i)
    packed[i] = {color.empty() ? 0.0f : color[i], beta.empty() ? 0.0f : beta[i]};
  scalars_.update(0, bytes_of(std::span<const glm::vec2>(packed)));
}

}  // namespace ibfvs
