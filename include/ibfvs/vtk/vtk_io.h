#pragma once
// The dataset formats of dataset_io.h through VTK's own readers and writers,
// from the VTK that Debian ships inside ParaView (paraview-dev 5.11: VTK 9.2).
// Its own library (ibfvs::vtk) so that ibfvs::core stays free of VTK; front
// ends call install_vtk_io() once, and the core's load_mesh, field sample:
// and the writers then reach it.
//
// Read: legacy .vtk (4.2 and 5.1 layouts, ASCII and binary, any dataset
// kind; arrays as SCALARS/VECTORS or FIELD data), XML of every kind (.vtp
// .vtu .vts .vtr .vti, their parallel .pvt*, .vtm multiblocks, .vtpd and
// .vtpc partitioned data), .pvd and .series time series, OpenFOAM cases
// (.foam or the case folder; boundary patches, time folders). Files are
// read in a child process (core/support/isolation.h): VTK's parser is the only one,
// and a crash or an allocation past the limit there is an error line. Polygons and quads are
// triangulated, strips unrolled, lines and vertices dropped; a volume shows
// its outer surface. Cell arrays reach the vertices area-weighted.

#include <filesystem>
#include <string>
#include <vector>

#include "ibfvs/core/mesh/dataset_io.h"

class vtkDataObject;

namespace ibfvs {
class SplitMemory;
}

namespace ibfvs::vtk {

/// Installs these readers and writers into the core (install_dataset_io)
/// and routes VTK's own messages into the errors they raise instead of
/// standard error. Idempotent.
void install_vtk_io();

/// The VTK version these readers come from, e.g. "9.2.20230111".
std::string vtk_version();

/// The surface of data already in memory (a host's, such as the geometry
/// ParaView hands a representation), as read() makes it of a file's: every
/// block's polygons triangulated or a volume's outer surface, blocks welded,
/// arrays by name (cell arrays area-weighted to the vertices), no normals
/// computed. With `cells_apart`, every triangle has three vertices of its
/// own instead, carrying its cell's values unaveraged (flat per cell, as
/// ParaView's Surface colours cell data), with the welded surface's smooth
/// normals; cell arrays then win over point arrays of the same name.
/// Leaves VTK's output window alone. Throws InputError starting with `name`
/// when there is no surface. With `memory`, polygons split as they did the
/// last time the same cells came (a host's next time step of a moving
/// mesh: the same triangles, core/mesh/polygon.h), and are kept there.
TriMesh surface_mesh(vtkDataObject* data, const std::string& name, bool cells_apart = false,
                     SplitMemory* memory = nullptr);

/// What dataset_io.h's functions do, callable directly.
Dataset read(const DatasetRequest& request);
VolumeSample sample(const std::filesystem::path& path, const std::string& array, std::size_t step,
                    const std::vector<glm::vec3>& points);
void write_polydata(const TriMesh& mesh, const std::vector<glm::vec2>* uv,
                    const std::filesystem::path& path, const std::string& texture);

}  // namespace ibfvs::vtk
