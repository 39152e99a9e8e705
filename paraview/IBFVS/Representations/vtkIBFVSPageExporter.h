// File > Export Scene's "ibfvs web page (*.html)" (ExportView("x.html") in
// Python): the view's visible IBFVS representations as the self-contained,
// animated page that `ibfvs render --out x.html` writes (the same runtime
// and the same pass). The page holds their surfaces and vectors at each of
// the data's times, their settings, ParaView's colours as drawn (colour map,
// range, log scale, point or cell data) and the view's camera, size and
// background.
//
// vtkSMIBFVSPageExporterProxy renders the view at each time and calls
// AddTimeStep(); Write() then writes the page. Without steps taken, Write()
// takes the view as it is. A problem (no IBFVS representation visible, one
// that draws the plain surface, a scene too large for a page, a name without
// .html) is one error line naming the file; nothing is written.
#ifndef vtkIBFVSPageExporter_h
#define vtkIBFVSPageExporter_h

#include "IBFVSRepresentationsModule.h"  // export macro
#include "vtkExporter.h"

class IBFVSREPRESENTATIONS_EXPORT vtkIBFVSPageExporter : public vtkExporter {
 public:
  static vtkIBFVSPageExporter* New();
  vtkTypeMacro(vtkIBFVSPageExporter, vtkExporter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The page's file, NAME.html.
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);

  /// The most triangles the page takes, over all its times' surfaces
  /// (beyond, a browser tab runs short of memory).
  vtkSetClampMacro(MaximumTriangles, int, 1, 100000000);
  vtkGetMacro(MaximumTriangles, int);

  /// The page's size in pixels (the view's ViewSize); 0: the renderer's.
  vtkSetVector2Macro(Size, int);
  vtkGetVector2Macro(Size, int);

  /// Takes the view's IBFVS surfaces as they were last drawn as the page's
  /// next time step.
  void AddTimeStep();
  /// Forgets the steps taken.
  void ClearTimeSteps();

 protected:
  vtkIBFVSPageExporter();
  ~vtkIBFVSPageExporter() override;

  void WriteData() override;

 private:
  vtkIBFVSPageExporter(const vtkIBFVSPageExporter&) = delete;
  void operator=(const vtkIBFVSPageExporter&) = delete;

  char* FileName = nullptr;
  int MaximumTriangles;  // ibfvs::WebPageLimits's
  int Size[2] = {0, 0};
  class Internals;
  Internals* Internal;
};

#endif
