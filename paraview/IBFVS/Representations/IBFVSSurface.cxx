// The mapper's surface: this process's piece of ParaView's data as the
// library's mesh with the chosen vectors, and ParaView's colour map at its
// vertices (vtkIBFVSMapper.cxx draws it).
#include "IBFVSSurface.h"

#include "ibfvs/core/image/colormap.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include <glm/geometric.hpp>

#include "ibfvs/vtk/vtk_io.h"

#include "vtkAbstractMapper.h"  // the scalar modes
#include "vtkColorTransferFunction.h"
#include "vtkDataObject.h"
#include "vtkLookupTable.h"
#include "vtkScalarsToColors.h"

namespace ibfvs::paraview {
namespace {

std::string array_names(const ibfvs::TriMesh& mesh) {
  std::string names;
  const auto add = [&](const std::string& name, int components) {
    names += (names.empty() ? "" : ", ") + name + " (" + std::to_string(components) + ")";
  };
  for (const auto& a : mesh.scalars) add(a.first, 1);
  for (const auto& a : mesh.vector_arrays) add(a.first, 3);
  for (const auto& a : mesh.other_arrays) add(a.first, a.second);
  return names.empty() ? "none" : names;
}

}  // namespace

// The surface of this rank's piece with the chosen vectors; `problem` says
// why there is none. An empty piece is no problem (null mesh).
std::shared_ptr<ibfvs::TriMesh> take_surface(vtkDataObject* input, const std::string& vectors,
                                             bool cells_apart, ibfvs::SplitMemory& splits,
                                             std::string& problem) {
  problem.clear();
  if (!input || input->GetNumberOfElements(vtkDataObject::POINT) == 0) {
    return nullptr;
  }
  try {
    auto mesh = std::make_shared<ibfvs::TriMesh>(
        ibfvs::vtk::surface_mesh(input, "the input", cells_apart, &splits));
    bool any_vectors = false;
    for (const auto& a : mesh->vector_arrays) any_vectors = any_vectors || a.first != "Normals";
    if (!any_vectors) {
      problem =
          "the data has no 3-component array to take as vectors (arrays: " + array_names(*mesh) +
          ")";
      return nullptr;
    }
    if (vectors.empty()) {
      problem =
          "no vector array chosen: set Vectors (SelectInputVectors) to a point or cell "
          "array of 3 components (arrays: " +
          array_names(*mesh) + ")";
      return nullptr;
    }
    const auto it = mesh->vector_arrays.find(vectors);
    if (it == mesh->vector_arrays.end()) {
      if (mesh->scalars.count(vectors))
        problem = "the array '" + vectors + "' has 1 component; IBFVS needs 3-component vectors";
      else if (const auto other = mesh->other_arrays.find(vectors);
               other != mesh->other_arrays.end())
        problem = "the array '" + vectors + "' has " + std::to_string(other->second) +
                  " components; IBFVS needs 3-component vectors";
      else
        problem = "no array named '" + vectors + "' (arrays: " + array_names(*mesh) + ")";
      return nullptr;
    }
    mesh->vectors = it->second;
    // Normals from the data where it has them (ParaView's geometry filter,
    // or a filter that computed them with ghost cells): pieces then shade
    // alike along their boundaries.
    if (const auto n = mesh->vector_arrays.find("Normals"); n != mesh->vector_arrays.end()) {
      mesh->normals = n->second;
      for (glm::vec3& v : mesh->normals) {
        const float l = glm::length(v);
        v = l > 0.0f && std::isfinite(l) ? v / l : glm::vec3(0.0f, 0.0f, 1.0f);
      }
    }
    return mesh;
  } catch (const std::exception& e) {
    problem = e.what();
    return nullptr;
  }
}

// Whether the Surface representation would colour by a cell array: what
// ParaView's ColorBy(("CELLS", name)) sets.
bool colours_cells(int scalar_mode) {
  return scalar_mode == VTK_SCALAR_MODE_USE_CELL_FIELD_DATA ||
         scalar_mode == VTK_SCALAR_MODE_USE_CELL_DATA;
}

// The colour ParaView's table gives values it cannot map (NaN).
std::optional<glm::vec3> nan_colour(vtkScalarsToColors* lut) {
  double c[3];
  if (auto* f = vtkColorTransferFunction::SafeDownCast(lut)) {
    f->GetNanColor(c);
  } else if (auto* t = vtkLookupTable::SafeDownCast(lut)) {
    const double* rgba = t->GetNanColor();
    std::copy(rgba, rgba + 3, c);
  } else {
    return std::nullopt;
  }
  return glm::vec3(c[0], c[1], c[2]);
}

// Positions in ParaView's lookup table for each vertex (of the prepared
// mesh, in its order), and the table at 256 points: the colour of a scalar
// the way the Surface representation maps it (linear or log scale,
// magnitude or component of a vector array). NaN stays NaN: the shader then
// shows the surface colour, which the caller sets to the table's NaN colour.
bool map_colours(const ibfvs::TriMesh& mesh, const char* name, vtkScalarsToColors* lut,
                 std::vector<float>& t, std::vector<glm::vec3>& table) {
  if (!name || !*name || !lut) return false;
  std::vector<float> values;
  if (const auto s = mesh.scalars.find(name); s != mesh.scalars.end()) {
    values = s->second;
  } else if (const auto v = mesh.vector_arrays.find(name); v != mesh.vector_arrays.end()) {
    const bool component = lut->GetVectorMode() == vtkScalarsToColors::COMPONENT;
    const int c = std::clamp(lut->GetVectorComponent(), 0, 2);
    values.reserve(v->second.size());
    for (const glm::vec3& x : v->second) values.push_back(component ? x[c] : glm::length(x));
  } else {
    return false;
  }
  const double* range = lut->GetRange();
  const bool log = lut->UsingLogScale() != 0 && range[0] > 0.0 && range[1] > 0.0;
  t = ibfvs::table_positions(values, range[0], range[1], log);
  const auto f = [log](double x) { return log ? std::log10(x) : x; };
  const double lo = f(range[0]), hi = f(range[1]);
  const double span = hi > lo ? hi - lo : 1.0;
  table.resize(256);
  for (int i = 0; i < 256; ++i) {
    const double u = lo + span * i / 255.0;
    double rgb[3];
    lut->GetColor(log ? std::pow(10.0, u) : u, rgb);
    table[static_cast<std::size_t>(i)] = glm::vec3(rgb[0], rgb[1], rgb[2]);
  }
  return true;
}

}  // namespace ibfvs::paraview
