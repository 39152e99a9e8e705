#include "vtkIBFVSPageExporter.h"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "IBFVSPage.h"
#include "IBFVSView.h"
#include "vtkIBFVSMapper.h"

#include "ibfvs/page/web_page.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkObjectFactory.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"

vtkStandardNewMacro(vtkIBFVSPageExporter);

class vtkIBFVSPageExporter::Internals {
 public:
  std::vector<std::vector<ibfvs::paraview::PageLayer>> steps;
  ibfvs::paraview::PageView view;
  std::string problem;  // the first met while taking the steps
};

vtkIBFVSPageExporter::vtkIBFVSPageExporter()
    : MaximumTriangles(static_cast<int>(ibfvs::WebPageLimits{}.triangles)),
      Internal(new Internals) {}

vtkIBFVSPageExporter::~vtkIBFVSPageExporter() {
  delete this->Internal;
  this->SetFileName(nullptr);
}

void vtkIBFVSPageExporter::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "MaximumTriangles: " << this->MaximumTriangles << "\n";
  os << indent << "Time steps taken: " << this->Internal->steps.size() << "\n";
}

void vtkIBFVSPageExporter::ClearTimeSteps() {
  this->Internal->steps.clear();
  this->Internal->problem.clear();
}

void vtkIBFVSPageExporter::AddTimeStep() {
  Internals& in = *this->Internal;
  vtkRenderer* ren = this->ActiveRenderer;
  if (!ren && this->RenderWindow) ren = this->RenderWindow->GetRenderers()->GetFirstRenderer();
  if (!ren) {
    if (in.problem.empty()) in.problem = "no view to export";
    return;
  }
  std::vector<ibfvs::paraview::PageLayer> layers;
  vtkActorCollection* actors = ren->GetActors();
  vtkCollectionSimpleIterator it;
  actors->InitTraversal(it);
  while (vtkActor* actor = actors->GetNextActor(it)) {
    auto* mapper = vtkIBFVSMapper::SafeDownCast(actor->GetMapper());
    if (!mapper || !actor->GetVisibility()) continue;
    ibfvs::paraview::PageLayer layer;
    std::string problem;
    if (!mapper->TakePageLayer(actor, layer, problem)) {
      if (in.problem.empty())
        in.problem = "an IBFVS representation draws the plain surface: " + problem;
      continue;
    }
    layers.push_back(std::move(layer));
  }
  in.steps.push_back(std::move(layers));

  // The view as it is now (the same at every time), at the page's size: the
  // view's (a window may be smaller than the view, as under a small X
  // screen), else the renderer's.
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  if (this->Size[0] > 0 && this->Size[1] > 0) {
    width = this->Size[0];
    height = this->Size[1];
  }
  width = std::max(width, 1);
  height = std::max(height, 1);
  in.view.camera = ibfvs::paraview::view_at_size(ren, width, height);
  double focal[3];
  ren->GetActiveCamera()->GetFocalPoint(focal);
  in.view.focal = glm::vec3(focal[0], focal[1], focal[2]);
  in.view.focal_distance = ren->GetActiveCamera()->GetDistance();
  in.view.width = width;
  in.view.height = height;
  double background[3];
  ren->GetBackground(background);
  for (ibfvs::paraview::PageLayer& layer : in.steps.back())
    layer.scene.background = glm::vec3(background[0], background[1], background[2]);
}

void vtkIBFVSPageExporter::WriteData() {
  Internals& in = *this->Internal;
  const std::string file = this->FileName ? this->FileName : "";
  if (in.steps.empty()) this->AddTimeStep();  // the view as it is
  try {
    if (file.empty()) throw ibfvs::InputError("no file name given");
    const std::string ext = std::filesystem::path(file).extension().string();
    if (ext != ".html" && ext != ".HTML" && ext != ".htm")
      throw ibfvs::InputError("a page must be named NAME.html");
    if (!in.problem.empty()) throw ibfvs::InputError(in.problem);
    const std::string name = std::filesystem::path(file).stem().string();
    const ibfvs::PreparedScene scene =
        ibfvs::paraview::page_scene(std::move(in.steps), in.view, name.empty() ? "page" : name);
    ibfvs::WebPageLimits limits;
    limits.triangles = static_cast<std::size_t>(this->MaximumTriangles);
    ibfvs::write_web_page(scene, file, limits);
  } catch (const std::exception& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    vtkErrorMacro(<< file << ": " << what);
  }
  this->ClearTimeSteps();
}
