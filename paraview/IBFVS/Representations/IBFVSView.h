// ParaView's camera as the library's view (vtkIBFVSMapper.cxx).
#ifndef IBFVSView_h
#define IBFVSView_h

#include "ibfvs/render/ibfvs_renderer.h"

class vtkActor;
class vtkRenderer;

namespace ibfvs::paraview {

/// The renderer's active camera and the actor's transform as the library's
/// view and projection matrices.
ibfvs::ViewState view_of(vtkRenderer* ren, vtkActor* actor);

/// World units a pixel spans at the camera's focal point, in a viewport of
/// width x height pixels (perspective or parallel projection, with the view
/// angle vertical or horizontal as the camera has it).
double world_per_pixel(vtkRenderer* ren, int width, int height);

}  // namespace ibfvs::paraview

#endif
