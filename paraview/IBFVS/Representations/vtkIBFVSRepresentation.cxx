#include "vtkIBFVSRepresentation.h"

#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkIBFVSMapper.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPVRenderView.h"

vtkStandardNewMacro(vtkIBFVSRepresentation);

vtkIBFVSRepresentation::vtkIBFVSRepresentation() {
  // The Surface representation's mappers give way to two IBFVS mappers (the
  // LOD one draws while the GUI interacts, with its own texture).
  this->Mapper->Delete();
  this->LODMapper->Delete();
  this->IBFVSMapper = vtkIBFVSMapper::New();
  this->IBFVSLODMapper = vtkIBFVSMapper::New();
  this->Mapper = this->IBFVSMapper;
  this->LODMapper = this->IBFVSLODMapper;
  vtkCompositeDataDisplayAttributes* attributes = vtkCompositeDataDisplayAttributes::New();
  this->IBFVSMapper->SetCompositeDataDisplayAttributes(attributes);
  this->IBFVSLODMapper->SetCompositeDataDisplayAttributes(attributes);
  attributes->Delete();
  this->SetupDefaults();
}

vtkIBFVSRepresentation::~vtkIBFVSRepresentation() = default;

void vtkIBFVSRepresentation::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
}

int vtkIBFVSRepresentation::ProcessViewRequest(vtkInformationRequestKey* request_type,
                                               vtkInformation* inInfo, vtkInformation* outInfo) {
  if (!this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo)) {
    return 0;
  }
  // The mapper composites the texture across the ranks every frame (MPI
  // collectives): every rank must render, also one whose piece is empty.
  if (request_type == vtkPVView::REQUEST_UPDATE()) {
    outInfo->Set(vtkPVRenderView::RENDER_EMPTY_IMAGES(), 1);
  }
  return 1;
}

void vtkIBFVSRepresentation::SelectInputVectors(int, int, int, int attributeMode,
                                                const char* name) {
  this->IBFVSMapper->SetVectors(attributeMode, name);
  this->IBFVSLODMapper->SetVectors(attributeMode, name);
}

// Each scene key's property (the XML's, from the keys' table): to both
// mappers by its host name, which is the property's (the build checks that
// these are the table's host keys: paraview/generate_xml.cpp); a value the
// key refuses is one error, from the first.
#define IBFVS_FORWARD(Name, Type)                                                            \
  void vtkIBFVSRepresentation::Set##Name(Type value) {                                       \
    if (this->IBFVSMapper->SetKey(#Name, value)) this->IBFVSLODMapper->SetKey(#Name, value); \
  }
IBFVS_FORWARD(Alpha, double)
IBFVS_FORWARD(Beta, double)
IBFVS_FORWARD(NoiseScale, double)
IBFVS_FORWARD(StepPixels, double)
IBFVS_FORWARD(TimeProfile, int)
IBFVS_FORWARD(NoiseRate, double)
IBFVS_FORWARD(ImageNormalize, int)
IBFVS_FORWARD(FilterLength, double)
IBFVS_FORWARD(Contrast, double)
IBFVS_FORWARD(Sharpen, double)
IBFVS_FORWARD(Resample, int)
IBFVS_FORWARD(FieldFrame, int)
IBFVS_FORWARD(Seed, int)
IBFVS_FORWARD(Overlay, int)
#undef IBFVS_FORWARD

void vtkIBFVSRepresentation::SetFramesPerStep(int frames) {
  this->IBFVSMapper->SetFramesPerStep(frames);
  this->IBFVSLODMapper->SetFramesPerStep(frames);
}

void vtkIBFVSRepresentation::RestartTexture() {
  this->IBFVSMapper->Restart();
  this->IBFVSLODMapper->Restart();
}

void vtkIBFVSRepresentation::SetGatherForPage(int on) {
  this->IBFVSMapper->SetGatherForPage(on);
  this->IBFVSLODMapper->SetGatherForPage(on);
}
