#pragma once
// Where a scene's mesh comes from: a file, a generated surface named by a spec
// (landscape, relief, globe, torus, cylinder), or the demo; then Loop
// subdivision and the one-time vertex order for the GPU.

#include <functional>
#include <string>
#include <vector>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

struct LoadedMesh {
  TriMesh mesh;
  std::string name;                  ///< what to call it in messages: the path, or the demo's name
  bool demo = false;                 ///< no path was given
  bool generated_landscape = false;  ///< made by `landscape[:SEED[:CONTROLS[:RESOLUTION]]]`
  std::size_t file_vertices = 0;     ///< vertex count as read, before subdivision
  /// topology_hash of the mesh as read (before subdivision and GPU order):
  /// a later state of it with this hash has the same triangles.
  std::uint64_t file_topology = 0;
  std::vector<unsigned> vertex_order;  ///< new index of each vertex (GPU order); empty: unchanged
  std::vector<std::string> warnings;   ///< what the reader repaired, or the demo's fallback
  /// A series (a .pvd, an OpenFOAM case's time folders, numbered files):
  /// the steps' times (2 or more), else empty.
  std::vector<double> step_times;
  /// The surface at step k as read (file order, before subdivision and GPU
  /// order): its points (which may move), triangles (which may differ from
  /// the first step's) and arrays; set with step_times.
  std::function<TriMesh(std::size_t)> read_step;
};

/// Reads `path` (the reader's warnings in `warnings`), or with an empty path the
/// demo: the fetched bunny, else the cow, else a procedural torus (saying so).
/// `landscape[:SEED[:CONTROLS[:RESOLUTION]]]`, when no such file exists, is a
/// B-spline height field over [-1, 1]^2 on a random CONTROLS x CONTROLS grid
/// (default seed 1, 8 controls, 256 cells), heights within +-0.3;
/// `landscape:FILE[:RESOLUTION]` takes the control heights from a text file,
/// one row of numbers per line (at least 4 x 4).
/// `globe[:LEVEL]` is a geodesic unit sphere (default level 6: 81,920
/// triangles), north at +Y, longitude 0 at +Z, for wind: fields.
/// `relief:FILE:VAR:LON0,LON1,LAT0,LAT1[:SCALE[:RESOLUTION]]` is a height field
/// of a netCDF lon/lat variable over a box (x east, -z north, the longer side
/// spanning [-1, 1], height SCALE * value, by default 0.1 at the largest
/// |value|), with the variable kept as a scalar of the same name.
/// `torus[:R,r]` is a torus lying flat around +Y (default R = 1, r = 0.4);
/// `cylinder[:RADIUS,LENGTH[,COUNT]]` is COUNT open cylinders along X stacked
/// along Y (default one, radius 0.3, length 3). Both are for the paper's
/// figures 3 and 4 and carry exact normals.
/// VTK and OpenFOAM datasets (dataset_io.h) are read with their arrays;
/// `blocks` picks blocks of a multiblock or patches of an OpenFOAM case. A
/// file name with `*` names a numbered series (`run_*.vtp`, `wss*.ply`): the
/// files that match, ordered by the last number in their names, are the steps
/// of an unsteady field on the first one's mesh.
/// Then subdivides `subdivide` times and, with `gpu_order`, orders the mesh for
/// the GPU's vertex cache (optimize_for_gpu). Throws InputError naming the
/// file, or SettingError("mesh", ...) for a malformed spec.
LoadedMesh load_mesh(const std::string& path, int subdivide, bool gpu_order = true,
                     const std::vector<std::string>& blocks = {});

/// A mesh the caller made (arrays, a host's data): validated (InputError
/// naming `name`), normals computed when it has none, then subdivided and
/// ordered like a file's.
LoadedMesh load_mesh(TriMesh mesh, const std::string& name, int subdivide, bool gpu_order = true);

/// Reads one mesh file of any format ibfvs knows (OFF OBJ PLY STL, and the
/// dataset formats), with its arrays. Throws InputError naming the file.
TriMesh read_any_mesh(const std::string& path, const std::vector<std::string>& blocks = {},
                      std::vector<std::string>* warnings = nullptr);

}  // namespace ibfvs
