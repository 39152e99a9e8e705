#include "ibfvs/render/export.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "ibfvs/core/image/image.h"
#include "ibfvs/core/mesh/dataset_io.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"

namespace ibfvs {
namespace fs = std::filesystem;

void check_export_path(const fs::path& path, const std::string& what) {
  const std::string ext = lower_extension(path.string());
  if (ext != ".obj" && ext != ".gltf" && ext != ".glb" && ext != ".vtp")
    throw InputError(what + ": must be a .obj, .gltf, .glb or .vtp file, got '" + path.string() +
                     "'");
  if (ext == ".vtp") require_dataset_io(path, what);
}

ExportReport export_textured_model(const IbfvsRenderer& renderer, const TriMesh& mesh,
                                   const fs::path& path) {
  check_export_path(path);
  const std::string ext = lower_extension(path.string());
  ExportReport report;
  fs::path png = path;
  png.replace_extension(".png");
  const ImageF tex = renderer.read_texture();
  ImageU8 rgb(tex.width, tex.height, 3);
  for (std::size_t i = 0; i < rgb.pixels.size() / 3; ++i)
    for (std::size_t c = 0; c < 3; ++c)
      rgb.pixels[i * 3 + c] = static_cast<std::uint8_t>(
          std::lround(std::clamp(tex.pixels[i * 4 + c], 0.0f, 1.0f) * 255.0f));
  write_png(rgb, png);
  std::vector<glm::vec2> uv(mesh.vertex_count());
  for (std::size_t i = 0; i < uv.size(); ++i) {
    const glm::vec2 px = project_to_pixels(renderer.texture_view_projection(), mesh.positions[i],
                                           tex.width, tex.height);
    const glm::vec2 t(px.x / static_cast<float>(tex.width), px.y / static_cast<float>(tex.height));
    uv[i] = glm::clamp(t, glm::vec2(0.0f), glm::vec2(1.0f));
    report.outside += uv[i] != t;
  }
  report.files.push_back(path);
  if (ext == ".obj") {
    write_obj_textured(mesh, uv, path, png.filename().string());
    report.files.push_back(fs::path(path).replace_extension(".mtl"));
  } else if (ext == ".vtp") {
    // For ParaView: texture coordinates TCoords, the PNG's name in field data.
    write_polydata(mesh, &uv, path, png.filename().string());
  } else {
    write_gltf_textured(mesh, uv, path, png);
    if (ext == ".gltf") report.files.push_back(fs::path(path).replace_extension(".bin"));
  }
  report.files.push_back(png);
  return report;
}

}  // namespace ibfvs
