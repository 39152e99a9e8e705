// A page of ParaView's view (vtkIBFVSPageExporter): the surfaces of its
// visible IBFVS representations at each of the data's times, as one scene of
// the ibfvs library, written as the page `ibfvs render --out x.html` writes
// (the same runtime and pass).
#ifndef IBFVSPage_h
#define IBFVSPage_h

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/scene.h"
#include "ibfvs/core/scene/scene_prep.h"

namespace ibfvs::paraview {

/// The scalar that carries ParaView's colours into the page: each vertex's
/// position in the colour table (NaN: the table's NaN colour).
inline constexpr const char* kTableColour = "ParaView colour";

/// One representation's surface as ParaView draws it at one time.
struct PageLayer {
  std::string name;              ///< what messages call it: its data's arrays
  ibfvs::TriMesh mesh;           ///< in world space (the actor's transform applied), with its
                                 ///< vectors, normals and kTableColour where coloured
  ibfvs::Scene scene;            ///< its settings; its surface colour, the view's background
  std::vector<glm::vec3> table;  ///< ParaView's colour map at 256 points; empty: uncoloured
  float speed = 0.0f;            ///< its fastest vector, world units
};

/// The view the page starts from.
struct PageView {
  ibfvs::ViewState camera;      ///< ParaView's matrices
  glm::vec3 focal{0.0f};        ///< the camera's focal point (the page turns about it)
  double focal_distance = 0.0;  ///< from the camera to the focal point, world units
  int width = 0, height = 0;
};

/// The page's scene: each time's layers (in `steps`, in time order) as one
/// surface, the times as an unsteady scene (points that move, triangles of
/// their own; one step where nothing shown changes), seen through
/// ParaView's camera. dt as the mapper's: the
/// fastest vector of all times moves Step pixels at the focal point. Throws
/// ibfvs::InputError: no layer, or layers that differ in a setting (a page
/// has one look).
ibfvs::PreparedScene page_scene(std::vector<std::vector<PageLayer>> steps, const PageView& view,
                                const std::string& name);

}  // namespace ibfvs::paraview

#endif
