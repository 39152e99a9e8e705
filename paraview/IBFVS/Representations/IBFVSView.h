// ParaView's camera as the library's view (vtkIBFVSMapper.cxx, and the
// page's, vtkIBFVSPageExporter.cxx).
#ifndef IBFVSView_h
#define IBFVSView_h

#include "ibfvs/render/ibfvs_renderer.h"

#include <glm/mat4x4.hpp>

class vtkActor;
class vtkMatrix4x4;
class vtkRenderer;

namespace ibfvs::paraview {

/// The renderer's active camera and the actor's transform as the library's
/// view and projection matrices.
ibfvs::ViewState view_of(vtkRenderer* ren, vtkActor* actor);

/// The renderer's active camera as the library's view and projection for an
/// image of width x height pixels (a page of the view: the view's size, not
/// necessarily its window's).
ibfvs::ViewState view_at_size(vtkRenderer* ren, int width, int height);

/// A VTK matrix (row-major, on column vectors) as glm's.
glm::mat4 to_glm(vtkMatrix4x4* m);

}  // namespace ibfvs::paraview

#endif
