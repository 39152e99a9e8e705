#pragma once
// Exporting the textured surface (paper section 3.7): the texture F_t as a
// PNG and each vertex's position in it as texture coordinates, in a model
// file other tools open (OBJ + MTL, glTF, GLB, VTK .vtp for ParaView).

#include <filesystem>
#include <string>
#include <vector>

#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/render/ibfvs_renderer.h"

namespace ibfvs {

/// What export_textured_model wrote.
struct ExportReport {
  std::vector<std::filesystem::path> files;  ///< the model (and .mtl, .bin) first, the PNG last
  std::size_t outside = 0;  ///< vertices outside the texture's view (coordinates clamped)
};

/// Throws InputError unless `path` ends in .obj, .gltf, .glb or .vtp (and, for
/// .vtp, the dataset formats are built in). `what` names the setting in the
/// message.
void check_export_path(const std::filesystem::path& path, const std::string& what = "export");

/// Writes `mesh` (the renderer's, in its vertex order) with the renderer's
/// current texture: F_t as 8-bit RGB in `<stem>.png` beside the model and
/// texture coordinates from the texture's view (the lock view once locked).
/// Throws InputError when a file cannot be written.
ExportReport export_textured_model(const IbfvsRenderer& renderer, const TriMesh& mesh,
                                   const std::filesystem::path& path);

}  // namespace ibfvs
