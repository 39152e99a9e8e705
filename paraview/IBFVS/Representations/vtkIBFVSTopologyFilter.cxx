#include "vtkIBFVSTopologyFilter.h"

#include <cmath>
#include <exception>
#include <string>
#include <vector>

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include "ibfvs/core/fields/topology.h"
#include "ibfvs/vtk/vtk_io.h"

vtkStandardNewMacro(vtkIBFVSTopologyFilter);

vtkIBFVSTopologyFilter::vtkIBFVSTopologyFilter()
    : MinimumStrength(ibfvs::LineOptions{}.min_strength),
      MinimumLength(ibfvs::LineOptions{}.min_length) {
  // The vectors: the first of the point or cell arrays, as Surface LIC's.
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS,
                               vtkDataSetAttributes::VECTORS);
}

void vtkIBFVSTopologyFilter::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Reverse: " << this->Reverse << "\n"
     << indent << "MinimumStrength: " << this->MinimumStrength << "\n"
     << indent << "MinimumLength: " << this->MinimumLength << "\n";
}

int vtkIBFVSTopologyFilter::FillInputPortInformation(int, vtkInformation* info) {
  // A dataset or a composite of them (an OpenFOAM case's patches): one surface.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

namespace {

template <class Array>
vtkNew<Array> named(const char* name, int components) {
  vtkNew<Array> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  return a;
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
  ibfvs::FlowTopology topology;
  try {
    const ibfvs::TriMesh mesh = ibfvs::vtk::surface_mesh(input, "Skin-Friction Topology");
    const auto it = mesh.vector_arrays.find(name);
    if (it == mesh.vector_arrays.end()) {
      vtkErrorMacro("Skin-Friction Topology: the surface has no 3-component array '" << name
                                                                                     << "'");
      return 0;
    }
    std::vector<glm::vec3> field = it->second;
    for (glm::vec3& v : field) {
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) v = glm::vec3(0.0f);
      if (this->Reverse) v = -v;
    }
    topology = ibfvs::find_topology(mesh, field, {this->MinimumStrength, this->MinimumLength});
    vtkNew<vtkStringArray> summary;
    summary->SetName("summary");
    summary->InsertNextValue(ibfvs::topology_summary(topology, mesh));
    output->GetFieldData()->AddArray(summary);
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  // The layout of write_topology_vtp: vertices, then lines.
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts, lines;
  auto kind = named<vtkIntArray>("kind", 1);
  auto strength = named<vtkDoubleArray>("strength", 1);
  auto index = named<vtkIntArray>("index", 1);
  auto magnitude = named<vtkFloatArray>("magnitude", 1);
  auto eigen = named<vtkDoubleArray>("eigenvalues", 4);
  auto normals = named<vtkFloatArray>("Normals", 3);
  for (const ibfvs::CriticalPoint& p : topology.critical.points) {
    const vtkIdType id = points->InsertNextPoint(p.position.x, p.position.y, p.position.z);
    verts->InsertNextCell(1, &id);
    kind->InsertNextValue(static_cast<int>(p.kind));
    strength->InsertNextValue(std::max(std::abs(p.eigen_real[0]), std::abs(p.eigen_real[1])));
    index->InsertNextValue(p.index);
    magnitude->InsertNextValue(0.0f);
    const double e[4] = {p.eigen_real[0], p.eigen_imag[0], p.eigen_real[1], p.eigen_imag[1]};
    eigen->InsertNextTuple(e);
    normals->InsertNextTuple3(p.normal.x, p.normal.y, p.normal.z);
  }
  for (const ibfvs::FeatureLine& l : topology.lines.lines) {
    std::vector<vtkIdType> ids;
    for (const ibfvs::LinePoint& p : l.points) {
      ids.push_back(points->InsertNextPoint(p.position.x, p.position.y, p.position.z));
      index->InsertNextValue(0);
      magnitude->InsertNextValue(p.magnitude);
      const double e[4] = {p.eigen[0], 0.0, p.eigen[1], 0.0};
      eigen->InsertNextTuple(e);
      normals->InsertNextTuple3(p.normal.x, p.normal.y, p.normal.z);
    }
    if (l.closed && !ids.empty()) ids.push_back(ids.front());
    lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    kind->InsertNextValue(static_cast<int>(l.kind));
    strength->InsertNextValue(l.strength);
  }
  output->SetPoints(points);
  output->SetVerts(verts);
  output->SetLines(lines);
  output->GetCellData()->AddArray(kind);
  output->GetCellData()->SetActiveScalars("kind");
  output->GetCellData()->AddArray(strength);
  output->GetPointData()->AddArray(index);
  output->GetPointData()->AddArray(magnitude);
  output->GetPointData()->AddArray(eigen);
  output->GetPointData()->SetNormals(normals);
  return 1;
}
