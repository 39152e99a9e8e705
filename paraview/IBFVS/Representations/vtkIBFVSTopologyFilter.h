// Filters > Skin-Friction Topology: a vector field's critical points and its
// separation and attachment lines on any surface ParaView holds (a
// multiblock of OpenFOAM patches too), laid out as `ibfvs topology` writes
// them (ibfvs/core/fields/topology_layout.h, the one layout): a vertex per
// critical point, a polyline per line; cell arrays kind, id, strength,
// length, origin and colour (the kinds' colours: shown as they are with Map
// Scalars off), point arrays index, magnitude, eigenvalues and Normals. It
// asks for the time step the pipeline asks for, so it plays with transient
// data like any filter; a feature keeps its id from a time step to the
// next (or the one before) while it lasts.
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

  /// The significance scale, a fraction of the surface's size
  /// (ibfvs::TopologyOptions::scale).
  vtkSetClampMacro(FeatureScale, double, 1e-6, 1.0);
  vtkGetMacro(FeatureScale, double);

  /// A line is kept where its neighbours converge onto it (diverge from it)
  /// by at least e^this along it.
  vtkSetClampMacro(MinimumStrength, double, 0.0, 1e6);
  vtkGetMacro(MinimumStrength, double);

  /// A line is kept when it is at least this many scales long.
  vtkSetClampMacro(MinimumLength, double, 0.0, 1e9);
  vtkGetMacro(MinimumLength, double);

 protected:
  vtkIBFVSTopologyFilter();
  ~vtkIBFVSTopologyFilter() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

 private:
  vtkIBFVSTopologyFilter(const vtkIBFVSTopologyFilter&) = delete;
  void operator=(const vtkIBFVSTopologyFilter&) = delete;
  bool Reverse = false;
  double FeatureScale;
  double MinimumStrength;
  double MinimumLength;
  // The last time step's features, for their ids at the next.
  class Previous;
  Previous* Last = nullptr;
};

#endif
