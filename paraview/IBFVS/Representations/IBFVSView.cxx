// ParaView's camera as the library's view (vtkIBFVSMapper.cxx).
#include "IBFVSView.h"

#include <algorithm>
#include <cmath>

#include <glm/mat4x4.hpp>

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLActor.h"
#include "vtkOpenGLCamera.h"
#include "vtkRenderer.h"

namespace ibfvs::paraview {
namespace {

glm::mat4 from_vtk_transposed(vtkMatrix4x4* m) {
  // GetKeyMatrices hands matrices transposed for OpenGL: their storage is
  // the column-major order glm reads.
  glm::mat4 out;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c][r] = static_cast<float>(m->GetElement(c, r));
  return out;
}

}  // namespace

glm::mat4 to_glm(vtkMatrix4x4* m) {
  glm::mat4 out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[c][r] = static_cast<float>(m->GetElement(r, c));
  return out;
}

ibfvs::ViewState view_at_size(vtkRenderer* ren, int width, int height) {
  vtkCamera* camera = ren->GetActiveCamera();
  const double aspect = static_cast<double>(std::max(width, 1)) / std::max(height, 1);
  return {to_glm(camera->GetModelViewTransformMatrix()),
          to_glm(camera->GetProjectionTransformMatrix(aspect, -1, 1))};
}

ibfvs::ViewState view_of(vtkRenderer* ren, vtkActor* actor) {
  vtkMatrix4x4 *wcvc = nullptr, *vcdc = nullptr, *wcdc = nullptr;
  vtkMatrix3x3* normal = nullptr;
  auto* camera = vtkOpenGLCamera::SafeDownCast(ren->GetActiveCamera());
  camera->GetKeyMatrices(ren, wcvc, normal, vcdc, wcdc);
  ibfvs::ViewState view{from_vtk_transposed(wcvc), from_vtk_transposed(vcdc)};
  if (!actor->GetIsIdentity()) {
    vtkMatrix4x4* mcwc = nullptr;
    vtkMatrix3x3* actor_normal = nullptr;
    static_cast<vtkOpenGLActor*>(actor)->GetKeyMatrices(mcwc, actor_normal);
    view.view = view.view * from_vtk_transposed(mcwc);
  }
  return view;
}

}  // namespace ibfvs::paraview
