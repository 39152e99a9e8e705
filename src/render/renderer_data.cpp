// The renderer's data: the surface (SurfaceBuffers, surface_buffers.h),
// the field's mix, the scalars and the surface image (the passes are in
// ibfvs_renderer.cpp).
#include <algorithm>
#include <string>
#include <vector>

#include "ibfvs/core/support/error.h"
#include "ibfvs/render/ibfvs_renderer.h"
#include "ibfvs/render/pass_settings.h"

namespace ibfvs {

void IbfvsRenderer::set_mesh(const TriMesh& mesh, std::span<const glm::vec3> field) {
  upload_mesh(mesh, field);
  reset();
}

void IbfvsRenderer::replace_mesh(const TriMesh& mesh, std::span<const glm::vec3> field) {
  upload_mesh(mesh, field);  // F_t, its depth and the frame count stay
}

void IbfvsRenderer::upload_mesh(const TriMesh& mesh, std::span<const glm::vec3> field) {
  surface_.upload(mesh, field);
  probe_ = shaders::probe_length(surface_.bounds().diagonal());
  cull_ = closed_orientation(mesh);
  field_mix_ = 0.0f;
}

void IbfvsRenderer::set_triangles(const TriMesh& mesh) {
  if (mesh.vertex_count() != surface_.vertex_count())
    throw InputError("renderer: other triangles need the same " +
                     std::to_string(surface_.vertex_count()) + " vertices, got " +
                     std::to_string(mesh.vertex_count()));
  surface_.set_triangles(mesh.triangles);
  cull_ = closed_orientation(mesh);
}

void IbfvsRenderer::set_surface_steps(std::span<const glm::vec3> positions,
                                      std::span<const glm::vec3> normals,
                                      std::span<const glm::vec3> next_positions,
                                      std::span<const glm::vec3> next_normals,
                                      const SurfaceMotion& motion) {
  surface_.set_steps(positions, normals, next_positions, next_normals, motion, has_previous_);
}

void IbfvsRenderer::point_drawn_attributes() {
  // Locked, before the first frame, after another mesh, advecting in the
  // current view or with a field that holds the surface's motion already:
  // no motion of the surface enters (the vertex is taken where it is drawn).
  surface_.point_drawn(carries_surface() && has_previous_ && surface_.drawn_this_mesh() &&
                       !locked_);
}

void IbfvsRenderer::set_field(std::span<const glm::vec3> field) {
  surface_.set_field(field);
  field_mix_ = 0.0f;
}

void IbfvsRenderer::set_field_steps(std::span<const glm::vec3> current,
                                    std::span<const glm::vec3> next) {
  surface_.set_field_steps(current, next);
}

void IbfvsRenderer::set_field_mix(float mix) {
  field_mix_ = std::clamp(mix, 0.0f, 1.0f);
}

void IbfvsRenderer::set_surface_image(const ImageU8& image, const glm::vec3& centre) {
  if (image.pixels.empty()) {
    surface_image_ = gl::Texture2D();
    return;
  }
  if (image.channels != 4) throw InputError("renderer: the surface image must be RGBA");
  gl::check_image_size(image.width, image.height, "surface_image");
  std::vector<float> rgba(image.pixels.size());
  for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = image.pixels[i] / 255.0f;
  surface_image_ = gl::Texture2D(image.width, image.height, gl::Format::RGBA8, true);
  surface_image_.upload_float(rgba, 4);
  image_centre_ = centre;
  ++settings_version_;
}

void IbfvsRenderer::set_scalars(std::span<const float> color, std::span<const float> beta) {
  surface_.set_scalars(color, beta);
}

}  // namespace ibfvs
