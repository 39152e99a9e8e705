// The mapper behind the "IBFVS" representation: ParaView's composite surface
// mapper whose Render() draws the surface with the ibfvs library's animated
// flow texture instead, one frame per call, in ParaView's own OpenGL context
// (the library's passes into its own framebuffers, then F and its depth into
// ParaView's). Without usable vectors it warns once and draws the plain
// surface (the superclass), as it does for picking.
//
// Under MPI every rank draws its piece; after each frame the texture image
// F_t (and F, for the contrast statistics) is composited by nearest depth
// across the ranks (ibfvs/core/image/composite.h) through VTK's global controller.
// The collectives run in every rank's Render(), empty pieces included (the
// representation asks ParaView to render empty images).
#ifndef vtkIBFVSMapper_h
#define vtkIBFVSMapper_h

#include "IBFVSRepresentationsModule.h"  // export macro
#include "vtkCompositePolyDataMapper2.h"

#include <string>  // for TakePageLayer

namespace ibfvs {
struct Scene;
namespace paraview {
struct PageLayer;
}  // namespace paraview
}  // namespace ibfvs

class IBFVSREPRESENTATIONS_EXPORT vtkIBFVSMapper : public vtkCompositePolyDataMapper2 {
 public:
  static vtkIBFVSMapper* New();
  vtkTypeMacro(vtkIBFVSMapper, vtkCompositePolyDataMapper2);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(vtkRenderer* ren, vtkActor* act) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

  /// The vector array: association 0 point data, 1 cell data.
  void SetVectors(int association, const char* name);

  /// The scene key a host calls `host` (ibfvs::SceneKey::host: Alpha,
  /// NoiseScale, ...), set to `value`: kept to the key's range, an
  /// enumeration's number, a flag's 0 or 1. A value the key refuses is an
  /// error and the setting stays: false.
  bool SetKey(const char* host, double value);
  /// At least this many texture frames for each change of the data (a time
  /// step): a change adds the frames that the renders since the last one
  /// fell short of, at the new data (Save Animation renders a step once;
  /// Play renders on), all of them where the points moved
  /// (ibfvs::FramePacer).
  void SetFramesPerStep(int frames);
  /// Starts the texture afresh from noise at the next render.
  void Restart();
  /// Under MPI, each render while on also gathers every process's piece on
  /// process 0, where a page of the view takes the whole surface
  /// (vtkSMIBFVSPageExporterProxy turns it on while it renders the times).
  void SetGatherForPage(int on);

  /// Frames drawn with the texture since it last started afresh.
  int GetFrame();
  /// Why the last Render() drew a plain surface; empty when it drew the texture.
  const char* GetProblem();

 protected:
  vtkIBFVSMapper();
  ~vtkIBFVSMapper() override;

 private:
  vtkIBFVSMapper(const vtkIBFVSMapper&) = delete;
  void operator=(const vtkIBFVSMapper&) = delete;

  void SetScene(const ibfvs::Scene& scene);
  void TakeSurface(vtkDataObject* input, vtkMTimeType input_time, bool cells_apart);
  void GiveSurface(vtkActor* actor, const char* colour_array);
  void ObserveRenderer(vtkRenderer* ren);
  void RedrawAfterFXAA();

  friend class vtkIBFVSPageExporter;
  /// The surface this mapper drew at its last render, for a page (in world
  /// space, coloured as drawn): false with `problem` saying why when it drew
  /// none, or the plain surface.
  bool TakePageLayer(vtkActor* actor, ibfvs::paraview::PageLayer& layer, std::string& problem);

  class Internals;
  Internals* Internal;
};

#endif
