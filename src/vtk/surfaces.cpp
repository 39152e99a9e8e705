// The surface of any VTK data object as one TriMesh: blocks collected and
// checked, each block's surface triangulated with its arrays, the blocks
// welded, cell arrays carried to the vertices or kept apart
// (src/vtk/internal.h).
#include "internal.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <mutex>
#include <new>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include <vtkAppendFilter.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCellTypes.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkGenericDataObjectReader.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkLogger.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkMultiPieceDataSet.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOpenFOAMReader.h>
#include <vtkOutputWindow.h>
#include <vtkPartitionedDataSet.h>
#include <vtkPartitionedDataSetCollection.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProbeFilter.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>
#include <vtkStringArray.h>
#include <vtkTriangleFilter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkVersion.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLGenericDataObjectReader.h>
#include <vtkXMLPartitionedDataSetCollectionReader.h>
#include <vtkXMLPartitionedDataSetReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtk_nlohmannjson.h>
#include VTK_NLOHMANN_JSON(json.hpp)

#include "ibfvs/core/mesh/polygon.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"
#include "ibfvs/core/support/isolation.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs::vtk::detail {
namespace fs = std::filesystem;
namespace {

// Connectivity in range and points finite, before any filter touches them.
void check_cells(vtkCellArray* cells, vtkIdType points, const char* what, const Guard& g) {
  if (!cells || cells->GetNumberOfCells() == 0) return;
  vtkDataArray* conn = cells->GetConnectivityArray();
  vtkDataArray* offsets = cells->GetOffsetsArray();
  const vtkIdType n = conn->GetNumberOfTuples();
  const auto check_ids = [&](const auto* ids) {
    const auto bad = std::find_if(ids, ids + n, [&](auto id) { return id < 0 || id >= points; });
    if (bad != ids + n)
      g.fail(std::string(what) + ": a cell refers to point " +
             std::to_string(static_cast<long long>(*bad)) + " but there are only " +
             std::to_string(points));
  };
  if (cells->IsStorage64Bit())
    check_ids(cells->GetConnectivityArray64()->GetPointer(0));
  else
    check_ids(cells->GetConnectivityArray32()->GetPointer(0));
  double last = 0.0;
  for (vtkIdType i = 0; i < offsets->GetNumberOfTuples(); ++i) {
    const double o = offsets->GetComponent(i, 0);
    if (o < last || o > static_cast<double>(n) || (i == 0 && o != 0.0))
      g.fail(std::string(what) + ": malformed cell list");
    last = o;
  }
}

// Every cell of an unstructured grid has as many points as its type has
// (VTK's surface filter reads a cell's points by its type: a triangle of two
// points crashed it, which fuzzing found), and a type VTK knows.
void check_cell_types(vtkUnstructuredGrid* ug, const std::string& where, const Guard& g) {
  vtkCellArray* cells = ug->GetCells();
  vtkUnsignedCharArray* types = ug->GetCellTypesArray();
  if (!cells || cells->GetNumberOfCells() == 0) return;
  if (!types || types->GetNumberOfTuples() != cells->GetNumberOfCells())
    g.fail(where + ": " + std::to_string(cells->GetNumberOfCells()) + " cells but " +
           std::to_string(types ? types->GetNumberOfTuples() : 0) + " cell types");
  // Points of the fixed-size types; at least that many (negative) for the others.
  static const std::map<int, int> kPoints = {{VTK_EMPTY_CELL, 0},
                                             {VTK_VERTEX, 1},
                                             {VTK_POLY_VERTEX, -1},
                                             {VTK_LINE, 2},
                                             {VTK_POLY_LINE, -2},
                                             {VTK_TRIANGLE, 3},
                                             {VTK_TRIANGLE_STRIP, -3},
                                             {VTK_POLYGON, -3},
                                             {VTK_PIXEL, 4},
                                             {VTK_QUAD, 4},
                                             {VTK_TETRA, 4},
                                             {VTK_VOXEL, 8},
                                             {VTK_HEXAHEDRON, 8},
                                             {VTK_WEDGE, 6},
                                             {VTK_PYRAMID, 5},
                                             {VTK_PENTAGONAL_PRISM, 10},
                                             {VTK_HEXAGONAL_PRISM, 12},
                                             {VTK_QUADRATIC_EDGE, 3},
                                             {VTK_QUADRATIC_TRIANGLE, 6},
                                             {VTK_QUADRATIC_QUAD, 8},
                                             {VTK_QUADRATIC_POLYGON, -6},
                                             {VTK_QUADRATIC_TETRA, 10},
                                             {VTK_QUADRATIC_HEXAHEDRON, 20},
                                             {VTK_QUADRATIC_WEDGE, 15},
                                             {VTK_QUADRATIC_PYRAMID, 13},
                                             {VTK_BIQUADRATIC_QUAD, 9},
                                             {VTK_TRIQUADRATIC_HEXAHEDRON, 27},
                                             {VTK_TRIQUADRATIC_PYRAMID, 19},
                                             {VTK_QUADRATIC_LINEAR_QUAD, 6},
                                             {VTK_QUADRATIC_LINEAR_WEDGE, 12},
                                             {VTK_BIQUADRATIC_QUADRATIC_WEDGE, 18},
                                             {VTK_BIQUADRATIC_QUADRATIC_HEXAHEDRON, 24},
                                             {VTK_BIQUADRATIC_TRIANGLE, 7},
                                             {VTK_CUBIC_LINE, 4},
                                             {VTK_CONVEX_POINT_SET, -1},
                                             {VTK_POLYHEDRON, -4},
                                             {VTK_LAGRANGE_CURVE, -2},
                                             {VTK_LAGRANGE_TRIANGLE, -3},
                                             {VTK_LAGRANGE_QUADRILATERAL, -4},
                                             {VTK_LAGRANGE_TETRAHEDRON, -4},
                                             {VTK_LAGRANGE_HEXAHEDRON, -8},
                                             {VTK_LAGRANGE_WEDGE, -6},
                                             {VTK_LAGRANGE_PYRAMID, -5},
                                             {VTK_BEZIER_CURVE, -2},
                                             {VTK_BEZIER_TRIANGLE, -3},
                                             {VTK_BEZIER_QUADRILATERAL, -4},
                                             {VTK_BEZIER_TETRAHEDRON, -4},
                                             {VTK_BEZIER_HEXAHEDRON, -8},
                                             {VTK_BEZIER_WEDGE, -6},
                                             {VTK_BEZIER_PYRAMID, -5}};
  for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c) {
    const int type = types->GetValue(c);
    const auto it = kPoints.find(type);
    if (it == kPoints.end())
      g.fail(where + ": cell " + std::to_string(c) + " has an unknown cell type, " +
             std::to_string(type));
    const vtkIdType size = cells->GetCellSize(c);
    if (it->second >= 0 ? size != it->second : size < -it->second)
      g.fail(where + ": cell " + std::to_string(c) + " (" +
             vtkCellTypes::GetClassNameFromTypeId(type) + ") has " + std::to_string(size) +
             " points; it needs " + (it->second < 0 ? "at least " : "") +
             std::to_string(std::abs(it->second)));
  }
}

// Flat arrays: name -> (components, values tuple after tuple).
using Arrays = std::map<std::string, std::pair<int, std::vector<float>>>;

void take_arrays(vtkFieldData* data, vtkIdType tuples, Arrays& out) {
  if (!data) return;
  for (int i = 0; i < data->GetNumberOfArrays(); ++i) {
    vtkDataArray* a = data->GetArray(i);
    if (!a || a->GetNumberOfTuples() != tuples) continue;
    std::string name = a->GetName() ? a->GetName() : "";
    if (name.empty()) name = "array" + std::to_string(i);
    if (name.rfind("vtk", 0) == 0) continue;  // vtkValidPointMask, vtkGhostType, ids
    const int c = a->GetNumberOfComponents();
    std::vector<float> values(static_cast<std::size_t>(tuples) * static_cast<std::size_t>(c));
    if (auto* f = vtkFloatArray::SafeDownCast(a)) {  // the common case: copy as it is
      std::copy_n(f->GetPointer(0), values.size(), values.begin());
      out[name] = {c, std::move(values)};
      continue;
    }
    std::vector<double> tuple(static_cast<std::size_t>(c));
    for (vtkIdType t = 0; t < tuples; ++t) {
      a->GetTuple(t, tuple.data());
      for (int k = 0; k < c; ++k)
        values[static_cast<std::size_t>(t) * static_cast<std::size_t>(c) +
               static_cast<std::size_t>(k)] =
            static_cast<float>(tuple[static_cast<std::size_t>(k)]);
    }
    out[name] = {c, std::move(values)};
  }
}

// One block's surface, triangulated: positions, triangles and both kinds of
// arrays (cell arrays per triangle).
struct Surface {
  std::vector<glm::vec3> positions;
  std::vector<Triangle> triangles;
  Arrays point_arrays, cell_arrays;
  std::size_t dropped = 0;  // degenerate triangles left out (PolygonSplit::dropped)
};

// A surface's polygons as triangles (core/mesh/polygon.h: split_polygons,
// or the split these very cells got before, from `memory`), straight from
// the cell array's offsets and connectivity in its 32- or 64-bit storage.
std::shared_ptr<const PolygonSplit> split_cells(vtkCellArray* polys,
                                                std::span<const glm::vec3> points,
                                                SplitMemory* memory) {
  const auto split = [&](const auto* offsets, const auto* connectivity) {
    using Index = std::remove_cvref_t<decltype(*offsets)>;
    const auto n = static_cast<std::size_t>(polys->GetNumberOfCells());
    const PolygonList<Index> list{
        std::span<const Index>(offsets, n + 1),
        std::span<const Index>(connectivity, static_cast<std::size_t>(offsets[n]))};
    return memory ? memory->split(list, points)
                  : std::make_shared<const PolygonSplit>(split_polygons(list, points));
  };
  if (!polys || polys->GetNumberOfCells() == 0) return std::make_shared<const PolygonSplit>();
  if (polys->IsStorage64Bit())
    return split(polys->GetOffsetsArray64()->GetPointer(0),
                 polys->GetConnectivityArray64()->GetPointer(0));
  return split(polys->GetOffsetsArray32()->GetPointer(0),
               polys->GetConnectivityArray32()->GetPointer(0));
}

// A surface of polygons, as it is: its points, the triangles (each polygon
// split as split_cells splits it), the arrays (a cell's values on each of
// its triangles).
Surface own_triangles(vtkPolyData* poly, SplitMemory* memory) {
  Surface s;
  const vtkIdType n = poly->GetNumberOfPoints();
  s.positions.resize(static_cast<std::size_t>(n));
  if (n == 0) return s;  // a surface filter's empty output has no points object
  if (auto* f = vtkFloatArray::SafeDownCast(poly->GetPoints()->GetData());
      f && f->GetNumberOfComponents() == 3) {  // the common case: copy as they are
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
    std::memcpy(s.positions.data(), f->GetPointer(0), s.positions.size() * sizeof(glm::vec3));
  } else {
    double p[3];
    for (vtkIdType i = 0; i < n; ++i) {
      poly->GetPoint(i, p);
      s.positions[static_cast<std::size_t>(i)] = glm::vec3(p[0], p[1], p[2]);
    }
  }
  const std::shared_ptr<const PolygonSplit> split =
      split_cells(poly->GetPolys(), s.positions, memory);
  s.triangles = split->triangles;
  s.dropped = split->dropped;
  take_arrays(poly->GetPointData(), n, s.point_arrays);
  Arrays cells;
  take_arrays(poly->GetCellData(), poly->GetNumberOfCells(), cells);
  // Each triangle's cell: vertices and lines come before the polygons.
  const auto first = static_cast<std::size_t>(poly->GetNumberOfVerts() + poly->GetNumberOfLines());
  for (auto& [name, array] : cells) {
    const auto c = static_cast<std::size_t>(array.first);
    std::vector<float> per_triangle(split->polygon.size() * c);
    for (std::size_t t = 0; t < split->polygon.size(); ++t)
      std::copy_n(
          array.second.begin() + static_cast<std::ptrdiff_t>((first + split->polygon[t]) * c), c,
          per_triangle.begin() + static_cast<std::ptrdiff_t>(t * c));
    s.cell_arrays[name] = {array.first, std::move(per_triangle)};
  }
  return s;
}

Surface block_surface(vtkDataSet* ds, SplitMemory* memory) {
  vtkSmartPointer<vtkPolyData> poly = vtkPolyData::SafeDownCast(ds);
  if (!poly) {
    vtkNew<vtkDataSetSurfaceFilter> surface;  // the outer surface of a volume
    surface->SetInputData(ds);
    surface->Update();
    poly = surface->GetOutput();
  }
  // Polygons are taken as they are, split by split_cells (VTK's triangle
  // filter would copy a mesh of triangles: a second on six million; and its
  // triangles of a polygon change as the polygon moves); strips go through
  // VTK's triangle filter; lines and vertices are dropped.
  if (poly->GetNumberOfStrips() == 0) return own_triangles(poly, memory);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(poly);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  triangles->Update();
  return own_triangles(triangles->GetOutput(), memory);
}

// Every triangle with three vertices of its own, so that its cells' values
// stay its own (flat, as Surface colours cells) instead of being averaged at
// shared vertices: point arrays and smooth normals (of the welded surface)
// copied to each triangle's corners, `per_triangle` arrays (one tuple per
// triangle) to all three.
TriMesh cells_kept_apart(TriMesh& welded, const Arrays& per_triangle) {
  compute_vertex_normals(welded);
  TriMesh out;
  const std::size_t n = welded.triangles.size();
  const auto gather = [&](const auto& values) {
    std::remove_cvref_t<decltype(values)> v(3 * n);
    for (std::size_t t = 0; t < n; ++t)
      for (std::size_t k = 0; k < 3; ++k) v[3 * t + k] = values[welded.triangles[t][k]];
    return v;
  };
  out.positions = gather(welded.positions);
  out.normals = gather(welded.normals);
  for (const auto& [name, v] : welded.scalars) out.scalars[name] = gather(v);
  for (const auto& [name, v] : welded.vector_arrays) out.vector_arrays[name] = gather(v);
  out.other_arrays = welded.other_arrays;
  out.triangles.resize(n);
  for (std::size_t t = 0; t < n; ++t) {
    const auto i = static_cast<std::uint32_t>(3 * t);
    out.triangles[t] = {i, i + 1, i + 2};
  }
  for (const auto& [name, a] : per_triangle) {
    const auto c = static_cast<std::size_t>(a.first);
    if (c == 1) {
      std::vector<float>& v = out.scalars[name];
      v.resize(3 * n);
      for (std::size_t t = 0; t < n; ++t) v[3 * t] = v[3 * t + 1] = v[3 * t + 2] = a.second[t];
    } else if (c == 3) {
      std::vector<glm::vec3>& v = out.vector_arrays[name];
      v.resize(3 * n);
      for (std::size_t t = 0; t < n; ++t)
        v[3 * t] = v[3 * t + 1] = v[3 * t + 2] =
            glm::vec3(a.second[3 * t], a.second[3 * t + 1], a.second[3 * t + 2]);
    } else {
      out.other_arrays[name] = a.first;
    }
  }
  return out;
}

// The blocks' surfaces as one mesh: points welded where blocks meet (the
// patches of an OpenFOAM case share their edges), arrays missing from a
// block NaN there, cell arrays carried to the vertices area-weighted.
TriMesh merge_surfaces(std::vector<Surface>& surfaces, const std::vector<std::string>& names,
                       std::vector<std::string>& warnings, const Guard& g, bool cells_apart) {
  TriMesh mesh;
  Arrays per_triangle;  // cells_apart: the cell arrays as they are
  const auto store = [&](const std::string& name, int c, std::vector<float> values, bool cell) {
    if (cell && cells_apart) {
      per_triangle[name] = {c, std::move(values)};
    } else if (c == 1) {
      mesh.scalars[name] = cell ? triangle_to_vertex(mesh, values) : std::move(values);
    } else if (c == 3) {
      std::vector<glm::vec3> v(values.size() / 3);
      for (std::size_t i = 0; i < v.size(); ++i)
        v[i] = glm::vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
      mesh.vector_arrays[name] = cell ? triangle_to_vertex(mesh, v) : std::move(v);
    } else {
      mesh.other_arrays[name] = c;
    }
  };
  if (surfaces.size() == 1) {  // one block: its arrays as they are, no copy per value
    Surface& s = surfaces[0];
    mesh.positions = std::move(s.positions);
    mesh.triangles = std::move(s.triangles);
    for (auto& [name, a] : s.point_arrays) store(name, a.first, std::move(a.second), false);
    for (auto& [name, a] : s.cell_arrays)
      if (cells_apart || (!mesh.scalars.count(name) && !mesh.vector_arrays.count(name)))
        store(name, a.first, std::move(a.second), true);  // point data wins, unless apart
    return cells_apart ? cells_kept_apart(mesh, per_triangle) : mesh;
  }
  std::map<std::string, int> point_comps, cell_comps;
  for (const Surface& s : surfaces) {
    for (const auto& [name, a] : s.point_arrays) point_comps.emplace(name, a.first);
    for (const auto& [name, a] : s.cell_arrays) cell_comps.emplace(name, a.first);
  }
  // A block with an array as cell data where others have it as point data
  // (foamToVTK -one-boundary: the patches' cell data beside the volume's
  // point data) gets it at its vertices, area-weighted, rather than NaN.
  for (Surface& s : surfaces) {
    for (const auto& [name, c] : point_comps) {
      const auto cell = s.cell_arrays.find(name);
      if (s.point_arrays.count(name) || cell == s.cell_arrays.end() || cell->second.first != c)
        continue;
      TriMesh shape;
      shape.positions = s.positions;
      shape.triangles = s.triangles;
      const auto n = static_cast<std::size_t>(c);
      std::vector<float> at_vertices(s.positions.size() * n);
      for (std::size_t k = 0; k < n; ++k) {
        std::vector<float> component(s.triangles.size());
        for (std::size_t t = 0; t < component.size(); ++t)
          component[t] = cell->second.second[t * n + k];
        const std::vector<float> v = triangle_to_vertex(shape, component);
        for (std::size_t i = 0; i < v.size(); ++i) at_vertices[i * n + k] = v[i];
      }
      s.point_arrays[name] = {c, std::move(at_vertices)};
    }
  }
  Arrays points, cells;
  for (const auto& [name, c] : point_comps) points[name].first = c;
  for (const auto& [name, c] : cell_comps) cells[name].first = c;
  const bool weld = surfaces.size() > 1;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> by_position;
  const auto key = [](const glm::vec3& p) {
    // The bits of equal points: -0 as +0 (a point on a turning part's axis
    // comes back as -0 at some steps, equal to +0 but of other bits, and
    // was then welded at some steps and not at others).
    const glm::vec3 q = p + glm::vec3(0.0f);
    std::uint32_t b[3];
    std::memcpy(b, &q, sizeof b);
    return (static_cast<std::uint64_t>(b[0]) * 0x9E3779B97F4A7C15ull) ^
           (static_cast<std::uint64_t>(b[1]) * 0xC2B2AE3D27D4EB4Full) ^ b[2];
  };
  for (std::size_t si = 0; si < surfaces.size(); ++si) {
    Surface& s = surfaces[si];
    std::vector<std::uint32_t> index(s.positions.size());
    for (std::size_t i = 0; i < s.positions.size(); ++i) {
      std::optional<std::uint32_t> same;
      if (weld)
        for (const std::uint32_t j : by_position[key(s.positions[i])])
          if (mesh.positions[j] == s.positions[i]) {
            same = j;
            break;
          }
      if (same) {
        index[i] = *same;
        continue;
      }
      index[i] = static_cast<std::uint32_t>(mesh.positions.size());
      if (weld) by_position[key(s.positions[i])].push_back(index[i]);
      mesh.positions.push_back(s.positions[i]);
      for (auto& [name, a] : points) {
        const auto c = static_cast<std::size_t>(a.first);
        const auto it = s.point_arrays.find(name);
        for (std::size_t k = 0; k < c; ++k)
          a.second.push_back(it != s.point_arrays.end() && it->second.first == a.first
                                 ? it->second.second[i * c + k]
                                 : std::nanf(""));
      }
    }
    for (const Triangle& t : s.triangles) {
      if (t[0] >= index.size() || t[1] >= index.size() || t[2] >= index.size())
        g.fail("a triangle refers to a point out of range");
      mesh.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
    }
    for (auto& [name, a] : cells) {
      const auto c = static_cast<std::size_t>(a.first);
      const auto it = s.cell_arrays.find(name);
      for (std::size_t t = 0; t < s.triangles.size(); ++t)
        for (std::size_t k = 0; k < c; ++k)
          a.second.push_back(it != s.cell_arrays.end() && it->second.first == a.first
                                 ? it->second.second[t * c + k]
                                 : std::nanf(""));
    }
    for (const auto& [name, c] : point_comps)
      if (!s.point_arrays.count(name) && surfaces.size() > 1)
        warnings.push_back(g.path().string() + ": block " + names[si] + " has no point array '" +
                           name + "' (NaN there)");
    s = Surface{};  // free as we go
  }
  // A face that two blocks share, once: the first block's (a boundary
  // patch's, before a volume's outer surface).
  // (Sorted by their corners, then by order: the first of equal ones kept.)
  std::vector<std::pair<std::array<std::uint32_t, 3>, std::size_t>> faces(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::array<std::uint32_t, 3> k = mesh.triangles[t];
    std::sort(k.begin(), k.end());
    faces[t] = {k, t};
  }
  std::sort(faces.begin(), faces.end());
  std::vector<bool> keep(mesh.triangles.size(), true);
  std::size_t repeated = 0;
  for (std::size_t i = 1; i < faces.size(); ++i)
    if (faces[i].first == faces[i - 1].first) {
      keep[faces[i].second] = false;
      ++repeated;
    }
  if (repeated > 0) {
    std::size_t out = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      if (keep[t]) mesh.triangles[out++] = mesh.triangles[t];
    mesh.triangles.resize(out);
    for (auto& [name, a] : cells) {
      const auto c = static_cast<std::size_t>(a.first);
      std::size_t o = 0;
      for (std::size_t t = 0; t < keep.size(); ++t)
        if (keep[t])
          for (std::size_t k = 0; k < c; ++k) a.second[o++] = a.second[t * c + k];
      a.second.resize(o);
    }
  }
  const std::size_t n = mesh.positions.size();
  for (auto& [name, a] : points) {
    if (a.second.size() != n * static_cast<std::size_t>(a.first)) continue;
    store(name, a.first, std::move(a.second), false);
  }
  for (auto& [name, a] : cells) {
    if (!cells_apart && (mesh.scalars.count(name) || mesh.vector_arrays.count(name)))
      continue;  // point data wins, unless apart
    store(name, a.first, std::move(a.second), true);
  }
  return cells_apart ? cells_kept_apart(mesh, per_triangle) : mesh;
}

}  // namespace

void collect_blocks(vtkDataObject* obj, const std::string& name, const std::string& path,
                    std::vector<Block>& out) {
  if (!obj) return;
  if (auto* mb = vtkMultiBlockDataSet::SafeDownCast(obj)) {
    for (unsigned i = 0; i < mb->GetNumberOfBlocks(); ++i) {
      std::string child = "block" + std::to_string(i);
      if (mb->HasMetaData(i) && mb->GetMetaData(i)->Has(vtkCompositeDataSet::NAME()))
        child = mb->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
      collect_blocks(mb->GetBlock(i), child, path.empty() ? child : path + "/" + child, out);
    }
  } else if (auto* mp = vtkMultiPieceDataSet::SafeDownCast(obj)) {
    for (unsigned i = 0; i < mp->GetNumberOfPieces(); ++i)
      collect_blocks(mp->GetPieceAsDataObject(i), name, path, out);
  } else if (auto* pc = vtkPartitionedDataSetCollection::SafeDownCast(obj)) {
    for (unsigned i = 0; i < pc->GetNumberOfPartitionedDataSets(); ++i) {
      std::string child = "block" + std::to_string(i);
      if (pc->HasMetaData(i) && pc->GetMetaData(i)->Has(vtkCompositeDataSet::NAME()))
        child = pc->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
      collect_blocks(pc->GetPartitionedDataSet(i), child, path.empty() ? child : path + "/" + child,
                     out);
    }
  } else if (auto* pd = vtkPartitionedDataSet::SafeDownCast(obj)) {
    for (unsigned i = 0; i < pd->GetNumberOfPartitions(); ++i)
      collect_blocks(pd->GetPartitionAsDataObject(i), name, path, out);
  } else if (auto* ds = vtkDataSet::SafeDownCast(obj)) {
    out.push_back({name, path, ds});
  }
}

void check_dataset(vtkDataSet* ds, const Block& b, const Guard& g) {
  const vtkIdType n = ds->GetNumberOfPoints();
  const std::string where = b.path.empty() ? std::string("the data") : "block " + b.path;
  if (auto* ps = vtkPointSet::SafeDownCast(ds); ps && ps->GetPoints()) {
    double p[3];
    for (vtkIdType i = 0; i < n; ++i) {
      ps->GetPoints()->GetPoint(i, p);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        g.fail(where + ": point " + std::to_string(i) +
               " has a non-finite coordinate (NaN or infinity)");
    }
  }
  if (auto* pd = vtkPolyData::SafeDownCast(ds)) {
    check_cells(pd->GetVerts(), n, where.c_str(), g);
    check_cells(pd->GetLines(), n, where.c_str(), g);
    check_cells(pd->GetPolys(), n, where.c_str(), g);
    check_cells(pd->GetStrips(), n, where.c_str(), g);
  } else if (auto* ug = vtkUnstructuredGrid::SafeDownCast(ds)) {
    check_cells(ug->GetCells(), n, where.c_str(), g);
    check_cell_types(ug, where, g);
    if (vtkIdTypeArray* faces = ug->GetFaces())
      if (faces->GetNumberOfTuples() > 0) {
        // Polyhedra: [nfaces, (npts, ids...)...] per cell; ids in range.
        const vtkIdType m = faces->GetNumberOfTuples();
        for (vtkIdType i = 0; i < m;) {
          const vtkIdType nf = faces->GetValue(i++);
          for (vtkIdType f = 0; f < nf && i < m; ++f) {
            const vtkIdType np = faces->GetValue(i++);
            for (vtkIdType k = 0; k < np && i < m; ++k, ++i)
              if (faces->GetValue(i) < 0 || faces->GetValue(i) >= n)
                g.fail(where + ": a polyhedron face refers to a point out of range");
          }
        }
      }
  }
}

// Surfaces of the selected blocks of a data object, merged into one mesh.
TriMesh surface_of(vtkDataObject* obj, const std::vector<std::string>& patterns,
                   std::vector<std::string>* block_names, std::vector<std::string>& warnings,
                   const Guard& g, bool patterns_applied, bool cells_apart, SplitMemory* memory,
                   std::size_t* dropped) {
  std::vector<Block> blocks;
  collect_blocks(obj, "", "", blocks);
  std::vector<Block> chosen;
  if (patterns.empty() || patterns_applied) {
    chosen = blocks;
  } else {
    std::vector<bool> used(patterns.size(), false);
    for (const Block& b : blocks) {
      bool on = false;
      for (std::size_t k = 0; k < patterns.size(); ++k)
        if (glob_match(patterns[k], b.name) || glob_match(patterns[k], b.path)) on = used[k] = true;
      if (on) chosen.push_back(b);
    }
    for (std::size_t k = 0; k < patterns.size(); ++k)
      if (!used[k]) {
        std::string known;
        for (const Block& b : blocks) known += (known.empty() ? "" : ", ") + b.path;
        if (blocks.size() == 1 && blocks[0].path.empty())
          g.fail("has no blocks to choose from (blocks '" + patterns[k] + "')");
        g.fail("no block matches '" + patterns[k] +
               "' (blocks: " + (known.empty() ? "none" : known) + ")");
      }
  }
  // Surfaces before volumes: where a volume's outer surface and a boundary
  // block coincide (foamToVTK writes both, internal.vtu and the patches),
  // the boundary's faces and arrays are the ones kept (merge_surfaces).
  std::stable_partition(chosen.begin(), chosen.end(), [](const Block& b) {
    return vtkPolyData::SafeDownCast(b.data) != nullptr;
  });
  std::vector<Surface> surfaces;
  std::vector<std::string> names;
  vtkIdType cells = 0, points = 0;
  for (const Block& b : chosen) {
    check_dataset(b.data, b, g);
    cells += b.data->GetNumberOfCells();
    points += b.data->GetNumberOfPoints();
    Surface s = block_surface(b.data, memory);
    g.check();
    if (dropped) *dropped += s.dropped;
    if (s.triangles.empty()) continue;
    surfaces.push_back(std::move(s));
    names.push_back(b.path.empty() ? "(the data)" : b.path);
  }
  if (surfaces.empty())
    g.fail("has no surface to show (" + std::to_string(points) + " points, " +
           std::to_string(cells) + (cells == 1 ? " cell" : " cells") +
           ", none of them a polygon, strip or volume cell" +
           (blocks.empty() ? std::string(", no data set at all") : std::string()) + ")");
  if (block_names) *block_names = names;
  TriMesh mesh = merge_surfaces(surfaces, names, warnings, g, cells_apart);
  return mesh;
}

}  // namespace ibfvs::vtk::detail
