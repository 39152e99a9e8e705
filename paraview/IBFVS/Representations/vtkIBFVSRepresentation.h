// The "IBFVS" representation: ParaView's Surface representation whose mapper
// paints the surface with an animated flow texture (Image Based Flow
// Visualization for Curved Surfaces, van Wijk 2003) through the ibfvs
// library. Everything else (colouring by ParaView's colour map, opacity,
// transforms, selection) is the Surface representation's.
//
// Each Render() of a view showing it advances the texture by one frame. Under
// MPI (pvbatch, pvserver) every rank draws its own piece and the texture
// image is composited across the ranks each frame (docs/paraview.md), so the
// picture equals the single process's.
#ifndef vtkIBFVSRepresentation_h
#define vtkIBFVSRepresentation_h

#include "IBFVSRepresentationsModule.h"  // export macro
#include "vtkGeometryRepresentationWithFaces.h"

class vtkIBFVSMapper;

class IBFVSREPRESENTATIONS_EXPORT vtkIBFVSRepresentation
    : public vtkGeometryRepresentationWithFaces {
 public:
  static vtkIBFVSRepresentation* New();
  vtkTypeMacro(vtkIBFVSRepresentation, vtkGeometryRepresentationWithFaces);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The vector array that drives the texture (point or cell data), as
  /// Surface LIC's SelectInputVectors.
  void SelectInputVectors(int, int, int, int attributeMode, const char* name);

  /// The texture (alpha, beta: paper equations 10-11; noise: 6-8): the
  /// scene keys' properties, each Set<its host name> (ibfvs::SceneKey::host),
  /// a double for a number key, else an int. ParaView's wrapping reads these
  /// declarations; the build holds them to the keys' table
  /// (paraview/generate_xml.cpp).
  void SetAlpha(double value);
  void SetBeta(double value);
  void SetNoiseScale(double pixels);
  void SetStepPixels(double pixels);
  void SetTimeProfile(int profile);
  void SetNoiseRate(double vg);
  void SetImageNormalize(int on);
  void SetFilterLength(double pixels);
  void SetContrast(double contrast);
  void SetSharpen(double k);
  void SetResample(int mode);     // ibfvs::Resample
  void SetFieldFrame(int frame);  // ibfvs::FieldFrame
  void SetSeed(int seed);
  void SetOverlay(int overlay);  // ibfvs::Overlay
  /// Texture frames a change of the data (a time step) is given at least.
  void SetFramesPerStep(int frames);
  /// Starts the texture afresh (the panel's Restart Texture button).
  void RestartTexture();
  /// Under MPI, renders gather the whole surface on process 0 for a page
  /// (vtkSMIBFVSPageExporterProxy, while it renders).
  void SetGatherForPage(int on);

  int ProcessViewRequest(vtkInformationRequestKey* request_type, vtkInformation* inInfo,
                         vtkInformation* outInfo) override;

 protected:
  vtkIBFVSRepresentation();
  ~vtkIBFVSRepresentation() override;

  vtkIBFVSMapper* IBFVSMapper;
  vtkIBFVSMapper* IBFVSLODMapper;

 private:
  vtkIBFVSRepresentation(const vtkIBFVSRepresentation&) = delete;
  void operator=(const vtkIBFVSRepresentation&) = delete;
};

#endif
