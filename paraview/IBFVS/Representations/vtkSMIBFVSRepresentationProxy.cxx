#include "vtkSMIBFVSRepresentationProxy.h"

#include "vtkObjectFactory.h"
#include "vtkSMPropertyLink.h"

vtkStandardNewMacro(vtkSMIBFVSRepresentationProxy);

namespace {
// vtkSMProxy::GetSubProxy is protected; a subclass may name it, and the
// member pointer it yields reaches the sibling subproxies of our parent.
struct SubProxyAccess : vtkSMProxy {
  static vtkSMProxy* Get(vtkSMProxy* proxy, const char* name) {
    vtkSMProxy* (vtkSMProxy::*get)(const char*) = &SubProxyAccess::GetSubProxy;
    return (proxy->*get)(name);
  }
};
}  // namespace

vtkSMIBFVSRepresentationProxy* vtkSMIBFVSRepresentationProxy::Of(vtkSMProxy* representation) {
  return representation ? vtkSMIBFVSRepresentationProxy::SafeDownCast(
                              SubProxyAccess::Get(representation, "IBFVSRepresentation"))
                        : nullptr;
}

vtkSMIBFVSRepresentationProxy::vtkSMIBFVSRepresentationProxy() = default;

vtkSMIBFVSRepresentationProxy::~vtkSMIBFVSRepresentationProxy() {
  if (this->ToLIC) {
    this->ToLIC->Delete();
  }
  if (this->FromLIC) {
    this->FromLIC->Delete();
  }
}

void vtkSMIBFVSRepresentationProxy::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Linked to Surface LIC: " << (this->ToLIC ? "yes" : "no") << "\n";
}

void vtkSMIBFVSRepresentationProxy::CreateVTKObjects() {
  this->Superclass::CreateVTKObjects();
  this->LinkSurfaceLICVectors();
}

void vtkSMIBFVSRepresentationProxy::UpdateVTKObjects() {
  this->LinkSurfaceLICVectors();  // Surface LIC may have come after this proxy
  this->Superclass::UpdateVTKObjects();
}

void vtkSMIBFVSRepresentationProxy::LinkSurfaceLICVectors() {
  if (this->ToLIC || !this->GetParentProxy() || !this->GetProperty("SelectInputVectors")) {
    return;
  }
  vtkSMProxy* lic = SubProxyAccess::Get(this->GetParentProxy(), "SurfaceLICRepresentation");
  if (!lic || !lic->GetProperty("SelectInputVectors")) {
    return;
  }
  this->ToLIC = vtkSMPropertyLink::New();
  this->ToLIC->AddLinkedProperty(this, "SelectInputVectors", vtkSMLink::INPUT);
  this->ToLIC->AddLinkedProperty(lic, "SelectInputVectors", vtkSMLink::OUTPUT);
  this->FromLIC = vtkSMPropertyLink::New();
  this->FromLIC->AddLinkedProperty(lic, "SelectInputVectors", vtkSMLink::INPUT);
  this->FromLIC->AddLinkedProperty(this, "SelectInputVectors", vtkSMLink::OUTPUT);
}
