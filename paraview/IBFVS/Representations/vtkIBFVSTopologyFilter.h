// Filters > Skin-Friction Topology: a vector field's critical points and its
// separation and attachment lines on any surface ParaView holds (a
// multiblock of OpenFOAM patches too), as `ibfvs topology` writes them
// (docs/cfd.md): a vertex per critical point, a polyline per line; cell
// arrays kind (1 saddle, 2 attracting node, 3 repelling node, 4 attracting
// focus, 5 repelling focus, 6 centre, 10 separation line, 11 attachment
// line) and strength, point arrays index, magnitude, eigenvalues and
// Normals. It asks for the time step the pipeline asks for, so it plays
// with transient data like any filter.
#ifndef vtkIBFVSTopologyFilter_h
#define vtkIBFVSTopologyFilter_h

#include "IBFVSRepresentationsModule.h"  // export macro
#include "vtkPolyDataAlgorithm.h"

class IBFVSREPRESENTATIONS_EXPORT vtkIBFVSTopologyFilter : public vtkPolyDataAlgorithm {
 public:
  static vtkIBFVSTopologyFilter* New();
  vtkTypeMacro(vtkIBFVSTopologyFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The flow reversed (OpenFOAM's wallShearStress points against the
  /// flow at the wall: its separation is the reverse's attachment).
  vtkSetMacro(Reverse, bool);
  vtkGetMacro(Reverse, bool);
  vtkBooleanMacro(Reverse, bool);

  /// A line is kept where the flow converges onto it (or diverges) at
  /// least this fraction of the field's RMS rate.
  vtkSetClampMacro(MinimumStrength, double, 0.0, 1e6);
  vtkGetMacro(MinimumStrength, double);

  /// A line is kept when it is at least this many mean edges long.
  vtkSetClampMacro(MinimumLength, double, 0.0, 1e9);
  vtkGetMacro(MinimumLength, double);

 protected:
  vtkIBFVSTopologyFilter();
  ~vtkIBFVSTopologyFilter() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

 private:
  vtkIBFVSTopologyFilter(const vtkIBFVSTopologyFilter&) = delete;
  void operator=(const vtkIBFVSTopologyFilter&) = delete;
  bool Reverse = false;
  double MinimumStrength;
  double MinimumLength;
};

#endif
