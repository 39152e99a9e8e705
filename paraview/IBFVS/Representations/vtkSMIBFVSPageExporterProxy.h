// The proxy of "ibfvs web page (*.html)" (vtkIBFVSPageExporter): renders the
// view at each of the data's times (the time keeper's, as Save Animation
// snaps to them) with the whole surface on this process (local rendering,
// as ParaView's own exporters force it in client-server), takes each time's
// surfaces, puts the view back at its time and writes the page.
#ifndef vtkSMIBFVSPageExporterProxy_h
#define vtkSMIBFVSPageExporterProxy_h

#include "IBFVSRepresentationsModule.h"  // export macro
#include "vtkSMRenderViewExporterProxy.h"

class IBFVSREPRESENTATIONS_EXPORT vtkSMIBFVSPageExporterProxy
    : public vtkSMRenderViewExporterProxy {
 public:
  static vtkSMIBFVSPageExporterProxy* New();
  vtkTypeMacro(vtkSMIBFVSPageExporterProxy, vtkSMRenderViewExporterProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Write() override;

 protected:
  vtkSMIBFVSPageExporterProxy();
  ~vtkSMIBFVSPageExporterProxy() override;

 private:
  vtkSMIBFVSPageExporterProxy(const vtkSMIBFVSPageExporterProxy&) = delete;
  void operator=(const vtkSMIBFVSPageExporterProxy&) = delete;
};

#endif
