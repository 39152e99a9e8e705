// The mapper's surface: this process's piece of ParaView's data as the
// library's mesh with the chosen vectors, and ParaView's colour map at its
// vertices, the way the Surface representation maps them.
#ifndef IBFVSSurface_h
#define IBFVSSurface_h

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/mesh/polygon.h"

class vtkDataObject;
class vtkScalarsToColors;

namespace ibfvs::paraview {

/// The surface of this process's piece with the chosen vectors (point or
/// cell data; `cells_apart`: triangles apart, for colouring by a cell
/// array), normals from the data where it has them. Null with `problem`
/// saying why when it cannot be drawn; null without a problem for an empty
/// piece. (Its fastest vector is HostFlow's, from the surface it is given.)
/// Polygons split as `splits` split the same cells before: the next time
/// step of a moving part gets the same triangles (core/mesh/polygon.h).
std::shared_ptr<ibfvs::TriMesh> take_surface(vtkDataObject* input, const std::string& vectors,
                                             bool cells_apart, ibfvs::SplitMemory& splits,
                                             std::string& problem);

/// Whether the Surface representation would colour by a cell array (what
/// ParaView's ColorBy(("CELLS", name)) sets).
bool colours_cells(int scalar_mode);

/// The colour ParaView's table gives values it cannot map (NaN).
std::optional<glm::vec3> nan_colour(vtkScalarsToColors* lut);

/// Positions `t` in ParaView's lookup table for each vertex of `mesh` (the
/// prepared mesh, in its order), and the table at 256 points: the colour of
/// array `name` the way the Surface representation maps it (linear or log
/// scale, magnitude or component of a vector array). NaN stays NaN (the
/// shader shows the surface colour, which the caller sets to nan_colour).
/// False when the mesh has no such array or there is no table.
bool map_colours(const ibfvs::TriMesh& mesh, const char* name, vtkScalarsToColors* lut,
                 std::vector<float>& t, std::vector<glm::vec3>& table);

}  // namespace ibfvs::paraview

#endif
