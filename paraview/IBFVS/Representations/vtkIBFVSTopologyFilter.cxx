#include "vtkIBFVSTopologyFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "ibfvs/core/fields/topology.h"
#include "ibfvs/core/fields/topology_layout.h"
#include "ibfvs/vtk/vtk_io.h"

vtkStandardNewMacro(vtkIBFVSTopologyFilter);

class vtkIBFVSTopologyFilter::Previous {
 public:
  ibfvs::FlowTopology topology;
  int step = -1;  // its index among the input's time steps
  int next_id = 0;
  vtkMTimeType settings_time = 0;
  std::string vectors;
  bool reverse = false;
};

vtkIBFVSTopologyFilter::vtkIBFVSTopologyFilter()
    : FeatureScale(ibfvs::TopologyOptions{}.scale),
      MinimumStrength(ibfvs::TopologyOptions{}.min_strength),
      MinimumLength(ibfvs::TopologyOptions{}.min_length) {
  // The vectors: the first of the point or cell arrays, as Surface LIC's.
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS,
                               vtkDataSetAttributes::VECTORS);
}

vtkIBFVSTopologyFilter::~vtkIBFVSTopologyFilter() {
  delete this->Last;
}

void vtkIBFVSTopologyFilter::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Reverse: " << this->Reverse << "\n"
     << indent << "FeatureScale: " << this->FeatureScale << "\n"
     << indent << "MinimumStrength: " << this->MinimumStrength << "\n"
     << indent << "MinimumLength: " << this->MinimumLength << "\n";
}

int vtkIBFVSTopologyFilter::FillInputPortInformation(int, vtkInformation* info) {
  // A dataset or a composite of them (an OpenFOAM case's patches): one surface.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

namespace {

template <class Array, class T>
vtkNew<Array> array_of(const char* name, int components, const std::vector<T>& values) {
  vtkNew<Array> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(
      static_cast<vtkIdType>(values.size() / static_cast<std::size_t>(components)));
  std::copy(values.begin(), values.end(), a->GetPointer(0));
  return a;
}

vtkNew<vtkCellArray> cells_of(const std::vector<std::int64_t>& offsets,
                              const std::vector<std::int64_t>& connectivity) {
  vtkNew<vtkIdTypeArray> off, conn;
  off->SetNumberOfTuples(static_cast<vtkIdType>(offsets.size() + 1));
  off->SetValue(0, 0);
  for (std::size_t i = 0; i < offsets.size(); ++i)
    off->SetValue(static_cast<vtkIdType>(i + 1), offsets[i]);
  conn->SetNumberOfTuples(static_cast<vtkIdType>(connectivity.size()));
  for (std::size_t i = 0; i < connectivity.size(); ++i)
    conn->SetValue(static_cast<vtkIdType>(i), connectivity[i]);
  vtkNew<vtkCellArray> cells;
  cells->SetData(off, conn);
  return cells;
}

}  // namespace

int vtkIBFVSTopologyFilter::RequestData(vtkInformation*, vtkInformationVector** inputs,
                                        vtkInformationVector* outputs) {
  vtkDataObject* input = vtkDataObject::GetData(inputs[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputs, 0);
  vtkInformation* array_info = this->GetInputArrayInformation(0);
  const char* name = array_info && array_info->Has(vtkDataObject::FIELD_NAME())
                         ? array_info->Get(vtkDataObject::FIELD_NAME())
                         : nullptr;
  if (!input || !name) {
    vtkErrorMacro("Skin-Friction Topology: choose the vector array (Vectors)");
    return 0;
  }
  // Which of the input's time steps this is: a feature keeps its id from
  // one step to the next (or the one before) of the same data and settings.
  int step = -1;
  vtkInformation* in_info = inputs[0]->GetInformationObject(0);
  vtkInformation* out_info = outputs->GetInformationObject(0);
  if (in_info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()) &&
      out_info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())) {
    const double t = out_info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
    const int n = in_info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    const double* times = in_info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    double best = std::numeric_limits<double>::max();
    for (int i = 0; i < n; ++i)
      if (std::abs(times[i] - t) < best) best = std::abs(times[i] - t), step = i;
  }
  ibfvs::TopologyLayout layout;
  try {
    const ibfvs::TriMesh mesh = ibfvs::vtk::surface_mesh(input, "Skin-Friction Topology");
    const auto it = mesh.vector_arrays.find(name);
    if (it == mesh.vector_arrays.end()) {
      vtkErrorMacro("Skin-Friction Topology: the surface has no 3-component array '" << name
                                                                                     << "'");
      return 0;
    }
    std::vector<glm::vec3> field = it->second;
    std::size_t not_finite = 0;
    for (glm::vec3& v : field) {
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
        v = glm::vec3(0.0f);
        ++not_finite;
      }
      if (this->Reverse) v = -v;
    }
    if (not_finite > 0)
      vtkWarningMacro("Skin-Friction Topology: " << not_finite << " of " << field.size()
                                                 << " vectors are not finite numbers; zero there");
    ibfvs::FlowTopology topology = ibfvs::find_topology(
        mesh, field, {this->FeatureScale, this->MinimumStrength, this->MinimumLength});
    Previous* last = this->Last;
    const bool follows = last && step >= 0 && last->step >= 0 && std::abs(step - last->step) == 1 &&
                         last->vectors == name && last->reverse == this->Reverse &&
                         last->settings_time == this->GetMTime();
    if (!last) last = this->Last = new Previous;
    if (follows) {
      ibfvs::carry_ids(last->topology, topology, last->next_id, 2.0 * topology.lines.scale);
    } else {
      last->next_id =
          static_cast<int>(topology.critical.points.size() + topology.lines.lines.size());
    }
    last->topology = topology;
    last->step = step;
    last->vectors = name;
    last->reverse = this->Reverse;
    last->settings_time = this->GetMTime();
    layout = ibfvs::topology_layout(topology, ibfvs::topology_summary(topology, mesh));
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  vtkNew<vtkPoints> points;
  points->SetData(array_of<vtkFloatArray>("Points", 3, layout.points));
  output->SetPoints(points);
  output->SetVerts(cells_of(layout.vert_offsets, layout.vert_connectivity));
  output->SetLines(cells_of(layout.line_offsets, layout.line_connectivity));
  // Cells: the vertices' values first, then the lines' (as VTK orders them).
  output->GetCellData()->AddArray(array_of<vtkIntArray>("kind", 1, layout.kind));
  output->GetCellData()->SetActiveScalars("kind");
  output->GetCellData()->AddArray(array_of<vtkIntArray>("id", 1, layout.id));
  output->GetCellData()->AddArray(array_of<vtkDoubleArray>("strength", 1, layout.strength));
  output->GetCellData()->AddArray(array_of<vtkDoubleArray>("length", 1, layout.length));
  output->GetCellData()->AddArray(array_of<vtkIntArray>("origin", 1, layout.origin));
  output->GetCellData()->AddArray(array_of<vtkUnsignedCharArray>("colour", 3, layout.colour));
  output->GetPointData()->AddArray(array_of<vtkIntArray>("index", 1, layout.index));
  output->GetPointData()->AddArray(array_of<vtkFloatArray>("magnitude", 1, layout.magnitude));
  output->GetPointData()->AddArray(array_of<vtkDoubleArray>("eigenvalues", 4, layout.eigenvalues));
  output->GetPointData()->SetNormals(array_of<vtkFloatArray>("Normals", 3, layout.normals));
  vtkNew<vtkStringArray> summary;
  summary->SetName("summary");
  summary->InsertNextValue(layout.summary);
  output->GetFieldData()->AddArray(summary);
  return 1;
}
