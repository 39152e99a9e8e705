#pragma once
// Reading triangle meshes (OFF, OBJ, PLY, STL) through OpenMesh, with checks
// that turn truncated or malformed files into clear errors.

#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// What the reader noticed but could repair; printed by the CLI as warnings.
struct MeshReadReport {
  std::size_t polygons_triangulated = 0;  ///< faces with more than three vertices
  std::size_t faces_skipped = 0;          ///< faces the library rejected (repeated vertices)
  std::size_t degenerate_removed = 0;     ///< zero-area triangles dropped
  std::size_t unreferenced_vertices = 0;  ///< vertices no triangle uses (kept, harmless)
  bool normals_from_file = false;         ///< false: angle-weighted normals were computed
  std::vector<std::string> warnings;      ///< one line each, already naming the file
};

/// Reads a mesh. The format follows the extension (.off, .obj, .ply, .stl,
/// case-insensitive). Polygons are triangulated, STL duplicate vertices merged
/// (by OpenMesh's STL reader), vertex normals computed when the file has none.
/// PLY vertex properties vx, vy, vz become `mesh.vectors`; every other scalar
/// vertex property (other than x y z nx ny nz and colours) goes into `mesh.scalars`.
/// Throws InputError naming the file for a missing, unreadable, truncated or
/// malformed file (bad counts, indices out of range, non-finite coordinates).
TriMesh read_mesh(const std::filesystem::path& path, MeshReadReport* report = nullptr);

/// Writes a Wavefront OBJ with per-vertex texture coordinates `uv` (one per
/// vertex), normals, and a material file `<stem>.mtl` whose diffuse map is
/// `texture_file` (a path relative to the OBJ). Throws InputError when a
/// file cannot be written.
void write_obj_textured(const TriMesh& mesh, const std::vector<glm::vec2>& uv,
                        const std::filesystem::path& path, const std::string& texture_file);

/// Writes a glTF 2.0 model of the mesh with per-vertex texture coordinates
/// `uv` (one per vertex, OpenGL convention: v = 0 at the image's bottom row;
/// flipped to glTF's top-left origin on writing), normals, and an unlit
/// material (KHR_materials_unlit) whose base colour texture is the PNG file
/// `texture_png`. A `.gltf` path writes JSON plus `<stem>.bin` and refers to
/// the PNG by its file name (it must lie beside the model); a `.glb` path
/// writes one binary file with the PNG embedded. Throws InputError when the
/// PNG cannot be read or a file cannot be written.
void write_gltf_textured(const TriMesh& mesh, const std::vector<glm::vec2>& uv,
                         const std::filesystem::path& path,
                         const std::filesystem::path& texture_png);

/// Writes an ASCII or binary little-endian PLY with positions, normals, the
/// vector field (vx vy vz) and all scalars. Throws InputError when the file
/// cannot be written.
void write_ply(const TriMesh& mesh, const std::filesystem::path& path, bool binary = true);

}  // namespace ibfvs
