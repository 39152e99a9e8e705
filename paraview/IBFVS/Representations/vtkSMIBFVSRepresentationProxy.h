// The client-side proxy of the IBFVS representation. Its one task: Surface
// LIC (ParaView's own plugin) and IBFVS both offer a property named
// SelectInputVectors on the same composite representation, and ParaView
// exposes only the last one loaded; this proxy links the two both ways, so
// that choosing the vectors drives whichever of the two is shown.
#ifndef vtkSMIBFVSRepresentationProxy_h
#define vtkSMIBFVSRepresentationProxy_h

#include "IBFVSRepresentationsModule.h"  // export macro
#include "vtkSMRepresentationProxy.h"

class vtkSMPropertyLink;

class IBFVSREPRESENTATIONS_EXPORT vtkSMIBFVSRepresentationProxy : public vtkSMRepresentationProxy {
 public:
  static vtkSMIBFVSRepresentationProxy* New();
  vtkTypeMacro(vtkSMIBFVSRepresentationProxy, vtkSMRepresentationProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void UpdateVTKObjects() override;

  /// The IBFVS representation of a view's representation (the subproxy of
  /// ParaView's GeometryRepresentation and its kin); null where it has none.
  static vtkSMIBFVSRepresentationProxy* Of(vtkSMProxy* representation);

 protected:
  vtkSMIBFVSRepresentationProxy();
  ~vtkSMIBFVSRepresentationProxy() override;
  void CreateVTKObjects() override;

 private:
  vtkSMIBFVSRepresentationProxy(const vtkSMIBFVSRepresentationProxy&) = delete;
  void operator=(const vtkSMIBFVSRepresentationProxy&) = delete;

  void LinkSurfaceLICVectors();
  vtkSMPropertyLink* ToLIC = nullptr;
  vtkSMPropertyLink* FromLIC = nullptr;
};

#endif
