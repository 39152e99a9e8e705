#include "vtkSMIBFVSPageExporterProxy.h"

#include <cfloat>
#include <vector>

#include "vtkIBFVSPageExporter.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSMIBFVSRepresentationProxy.h"
#include "vtkSMParaViewPipelineController.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSession.h"

vtkStandardNewMacro(vtkSMIBFVSPageExporterProxy);

namespace {

// Under MPI (pvbatch, a server's renders): while on, each render of the
// view's IBFVS representations gathers their whole surface on the first
// process, where this exporter takes it.
void gather_for_page(vtkSMProxy* view, bool on) {
  vtkSMPropertyHelper representations(view, "Representations");
  for (unsigned int k = 0; k < representations.GetNumberOfElements(); ++k) {
    vtkSMProxy* ibfvs = vtkSMIBFVSRepresentationProxy::Of(representations.GetAsProxy(k));
    if (!ibfvs || !ibfvs->GetProperty("GatherForPage")) continue;
    vtkSMPropertyHelper(ibfvs, "GatherForPage").Set(on ? 1 : 0);
    ibfvs->UpdateVTKObjects();
  }
}

}  // namespace

vtkSMIBFVSPageExporterProxy::vtkSMIBFVSPageExporterProxy() = default;
vtkSMIBFVSPageExporterProxy::~vtkSMIBFVSPageExporterProxy() = default;

void vtkSMIBFVSPageExporterProxy::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
}

void vtkSMIBFVSPageExporterProxy::Write() {
  this->CreateVTKObjects();
  auto* exporter = vtkIBFVSPageExporter::SafeDownCast(this->GetClientSideObject());
  auto* view = vtkSMRenderViewProxy::SafeDownCast(this->View);
  if (!exporter || !view) return;
  view->GetSession()->PrepareProgress();

  // The whole surface on this process: rendered here, not on a server.
  vtkSMProperty* threshold = view->GetProperty("RemoteRenderThreshold");
  const double old_threshold = threshold ? vtkSMPropertyHelper(threshold).GetAsDouble() : 0.0;
  if (threshold) {
    vtkSMPropertyHelper(threshold).Set(DBL_MAX);
    view->UpdateVTKObjects();
  }
  gather_for_page(view, true);
  exporter->SetRenderWindow(view->GetRenderWindow());
  exporter->SetActiveRenderer(view->GetRenderer());
  exporter->ClearTimeSteps();
  if (view->GetProperty("ViewSize")) {
    vtkSMPropertyHelper size(view, "ViewSize");
    exporter->SetSize(size.GetAsInt(0), size.GetAsInt(1));
  }

  // Each of the data's times at its own data, then the view's time again.
  std::vector<double> times;
  vtkNew<vtkSMParaViewPipelineController> controller;
  if (vtkSMProxy* keeper = controller->FindTimeKeeper(view->GetSession()))
    times = vtkSMPropertyHelper(keeper, "TimestepValues").GetDoubleArray();
  vtkSMPropertyHelper view_time(view, "ViewTime");
  const double now = view_time.GetAsDouble();
  if (times.size() < 2) {
    view->StillRender();
    exporter->AddTimeStep();
  } else {
    for (const double t : times) {
      view_time.Set(t);
      view->UpdateVTKObjects();
      view->StillRender();
      exporter->AddTimeStep();
    }
    view_time.Set(now);
    view->UpdateVTKObjects();
  }
  gather_for_page(view, false);
  exporter->Write();  // an error line where the page cannot be written
  exporter->SetRenderWindow(nullptr);
  exporter->SetActiveRenderer(nullptr);

  if (threshold) {
    vtkSMPropertyHelper(threshold).Set(old_threshold);
    view->UpdateVTKObjects();
  }
  view->StillRender();
  view->GetSession()->CleanupPendingProgress();
}
