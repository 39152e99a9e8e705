#pragma once
// Datasets in formats the core does not read itself: VTK legacy (.vtk), XML
// (.vtp .vtu .vtm), .pvd series and OpenFOAM cases (a .foam file or the case
// folder). The core knows them by name and calls the implementation that the
// ibfvs::vtk library installs (ibfvs/vtk/vtk_io.h: install_vtk_io(), which
// front ends call once at start); a build without ParaView's VTK has none,
// and reading such a file says so in one line.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// What to read from a dataset.
struct DatasetRequest {
  std::filesystem::path path;
  /// Blocks of a multiblock (.vtm) or patches of an OpenFOAM case, by name
  /// or glob pattern (* and ?), matched against the block's name and its
  /// path ("boundary/wing"); empty: every block with a surface (OpenFOAM:
  /// every boundary patch, not the internal mesh).
  std::vector<std::string> blocks;
};

/// A surface read from a dataset: triangles, its point and cell arrays
/// carried to the vertices (1 component: `mesh.scalars`, 3: `vector_arrays`,
/// others named in `other_arrays`), and the time steps when it has several.
struct Dataset {
  TriMesh mesh;
  std::vector<std::string> blocks;  ///< the blocks read, for messages
  std::vector<double> times;        ///< the steps' time values; fewer than 2: steady
  /// The surface at step k (0 <= k < times.size()) with its arrays: the
  /// same vertices in the same order as `mesh` where the mesh is fixed or
  /// moves (its points may differ), others where it changes; throws
  /// InputError naming the file.
  std::function<TriMesh(std::size_t)> step;
  std::vector<std::string> warnings;  ///< what was repaired or skipped, naming the file
};

/// A vector array of a volume dataset sampled at points.
struct VolumeSample {
  std::vector<glm::vec3> values;    ///< one per point; zero where not found
  std::vector<std::uint8_t> found;  ///< 1 where the point lies inside the volume
};

/// The implementation of the dataset formats (ibfvs::vtk).
struct DatasetIo {
  std::function<Dataset(const DatasetRequest&)> read;
  /// The vector array `array` of the volume dataset `path` (time step
  /// `step`, counting from 0) interpolated at `points`.
  std::function<VolumeSample(const std::filesystem::path& path, const std::string& array,
                             std::size_t step, const std::vector<glm::vec3>& points)>
      sample;
  /// Writes the mesh, its normals, vectors and arrays as VTK XML PolyData;
  /// with `uv` (one per vertex) as texture coordinates, and `texture` (a
  /// file name) recorded as field data.
  std::function<void(const TriMesh&, const std::vector<glm::vec2>* uv, const std::filesystem::path&,
                     const std::string& texture)>
      write_polydata;
};

/// Installs the implementation (the ibfvs::vtk library does).
void install_dataset_io(DatasetIo io);

/// True when the implementation is installed.
bool dataset_io_available();

/// Throws InputError "[WHAT: ]PATH: VTK and OpenFOAM files need ibfvs built
/// with ParaView's VTK ..." unless the implementation is installed.
void require_dataset_io(const std::filesystem::path& path, const std::string& what = {});

/// The extensions of the VTK formats and series (lower case, with the dot):
/// the one table for is_dataset_path and for help texts.
const std::vector<std::string>& dataset_extensions();

/// dataset_extensions() as one line, ".vtk .vtp ... .series".
std::string dataset_extensions_text();

/// True for a path the dataset formats read: dataset_extensions(), .foam
/// (any case) or a folder holding an OpenFOAM case (system/controlDict).
bool is_dataset_path(const std::filesystem::path& path);

/// Reads a dataset's surface. Throws InputError naming the file, also when
/// this build has no dataset formats.
Dataset read_dataset(const DatasetRequest& request);

/// Samples a volume dataset's vector array at points. Throws InputError
/// naming the file, also when this build has no dataset formats.
VolumeSample sample_volume(const std::filesystem::path& path, const std::string& array,
                           std::size_t step, const std::vector<glm::vec3>& points);

/// Writes VTK XML PolyData (.vtp). Throws InputError naming the file, also
/// when this build has no dataset formats.
void write_polydata(const TriMesh& mesh, const std::vector<glm::vec2>* uv,
                    const std::filesystem::path& path, const std::string& texture = {});

}  // namespace ibfvs
