// The topology's summary line and its VTK XML PolyData file (topology.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "ibfvs/core/fields/topology.h"
#include "ibfvs/core/fields/topology_layout.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

constexpr CriticalKind kPointKinds[] = {CriticalKind::Saddle,         CriticalKind::AttractingNode,
                                        CriticalKind::RepellingNode,  CriticalKind::AttractingFocus,
                                        CriticalKind::RepellingFocus, CriticalKind::Centre};

std::string counted(std::size_t n, const std::string& one) {
  // "1 saddle", "2 saddles", "2 attracting foci", "3 centres".
  std::string many = one;
  if (many.size() > 3 && many.compare(many.size() - 3, 3, "cus") == 0)
    many.replace(many.size() - 2, 2, "i");
  else
    many += "s";
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

void data_array(std::ostream& out, const char* type, const char* name, int components,
                const std::string& values) {
  out << "        <DataArray type=\"" << type << "\"";
  if (name) out << " Name=\"" << name << "\"";
  if (components > 1) out << " NumberOfComponents=\"" << components << "\"";
  out << " format=\"ascii\">\n" << values << "\n        </DataArray>\n";
}

}  // namespace

std::string topology_summary(const FlowTopology& t, const TriMesh& mesh) {
  std::string kinds;
  for (const CriticalKind k : kPointKinds)
    if (t.count(k) > 0) kinds += (kinds.empty() ? "" : ", ") + counted(t.count(k), kind_name(k));
  std::string s = counted(t.critical.points.size(), "critical point") +
                  (kinds.empty() ? "" : " (" + kinds + ")") + ", " +
                  counted(t.count(LineKind::Separation), "separation line") + ", " +
                  counted(t.count(LineKind::Attachment), "attachment line") + "; index sum " +
                  std::to_string(t.critical.index_sum);
  // Poincare-Hopf holds on closed surfaces; an open one's boundary takes part.
  const Topology shape = analyze_topology(mesh);
  if (shape.boundary_edges == 0)
    s += " (Euler characteristic " + std::to_string(euler_characteristic(mesh)) + ")";
  else
    s += " (an open surface, " + counted(shape.boundary_loops, "boundary loop") +
         ": no sum to expect)";
  if (t.critical.cancelled > 0)
    s += "; " + std::to_string(t.critical.cancelled) +
         " zeros cancelled in pairs closer than the scale";
  if (t.critical.on_lines > 0)
    s += "; " + std::to_string(t.critical.on_lines) + " zeros on lines of zeros";
  if (t.critical.zero_triangles > 0)
    s += "; the field is zero on " + std::to_string(t.critical.zero_triangles) + " triangles";
  if (t.critical.degenerate_triangles > 0)
    s += "; " + std::to_string(t.critical.degenerate_triangles) +
         " triangles without an isolated zero or area left out";
  return s;
}

TopologyLayout topology_layout(const FlowTopology& t, std::string summary) {
  TopologyLayout g;
  g.summary = std::move(summary);
  const auto cell = [&](int kind, int id, int origin, double strength, double length) {
    g.kind.push_back(kind);
    g.id.push_back(id);
    g.origin.push_back(origin);
    g.strength.push_back(strength);
    g.length.push_back(length);
    const auto rgb = kind_colour(kind);
    g.colour.insert(g.colour.end(), rgb.begin(), rgb.end());
  };
  std::int64_t id = 0;
  for (const CriticalPoint& p : t.critical.points) {
    g.points.insert(g.points.end(), {p.position.x, p.position.y, p.position.z});
    g.normals.insert(g.normals.end(), {p.normal.x, p.normal.y, p.normal.z});
    g.index.push_back(p.index);
    g.magnitude.push_back(0.0f);
    g.eigenvalues.insert(g.eigenvalues.end(),
                         {p.eigen_real[0], p.eigen_imag[0], p.eigen_real[1], p.eigen_imag[1]});
    g.vert_connectivity.push_back(id++);
    g.vert_offsets.push_back(id);
    cell(static_cast<int>(p.kind), p.id, 0, p.strength(), 0.0);
  }
  std::int64_t end = 0;
  for (const FeatureLine& l : t.lines.lines) {
    const std::int64_t first = id;
    for (const LinePoint& p : l.points) {
      g.points.insert(g.points.end(), {p.position.x, p.position.y, p.position.z});
      g.normals.insert(g.normals.end(), {p.normal.x, p.normal.y, p.normal.z});
      g.index.push_back(0);
      g.magnitude.push_back(p.magnitude);
      g.eigenvalues.insert(g.eigenvalues.end(), {p.eigen[0], 0.0, p.eigen[1], 0.0});
      g.line_connectivity.push_back(id++);
    }
    if (l.closed && !l.points.empty()) g.line_connectivity.push_back(first);
    end += static_cast<std::int64_t>(l.points.size()) + (l.closed && !l.points.empty() ? 1 : 0);
    g.line_offsets.push_back(end);
    cell(static_cast<int>(l.kind), l.id, static_cast<int>(l.origin), l.strength, l.length);
  }
  return g;
}

void write_topology_vtp(const TopologyLayout& g, const std::string& path) {
  const auto join = [](const auto& values) {
    std::string s;
    char b[40];
    for (const auto v : values) {
      if constexpr (std::is_floating_point_v<std::decay_t<decltype(v)>>)
        std::snprintf(b, sizeof b, "%.9g ", static_cast<double>(v));
      else
        std::snprintf(b, sizeof b, "%lld ", static_cast<long long>(v));
      s += b;
    }
    return s;
  };
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <PolyData>\n";
  // The summary as field data: a string array of one value (its characters'
  // codes, as VTK's XML writer stores strings, each ended by a 0).
  std::vector<int> chars(g.summary.begin(), g.summary.end());
  for (int& c : chars) c = static_cast<unsigned char>(c);
  chars.push_back(0);
  out << "    <FieldData>\n        <DataArray type=\"String\" Name=\"summary\" "
         "NumberOfTuples=\"1\" format=\"ascii\">\n"
      << join(chars) << "\n        </DataArray>\n    </FieldData>\n";
  out << "    <Piece NumberOfPoints=\"" << g.point_count() << "\" NumberOfVerts=\""
      << g.vert_offsets.size() << "\" NumberOfLines=\"" << g.line_offsets.size()
      << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  out << "      <Points>\n";
  data_array(out, "Float32", "Points", 3, join(g.points));
  out << "      </Points>\n      <PointData Scalars=\"index\" Normals=\"Normals\">\n";
  data_array(out, "Int32", "index", 1, join(g.index));
  data_array(out, "Float32", "magnitude", 1, join(g.magnitude));
  data_array(out, "Float64", "eigenvalues", 4, join(g.eigenvalues));
  data_array(out, "Float32", "Normals", 3, join(g.normals));
  out << "      </PointData>\n      <CellData Scalars=\"kind\">\n";
  data_array(out, "Int32", "kind", 1, join(g.kind));
  data_array(out, "Int32", "id", 1, join(g.id));
  data_array(out, "Float64", "strength", 1, join(g.strength));
  data_array(out, "Float64", "length", 1, join(g.length));
  data_array(out, "Int32", "origin", 1, join(g.origin));
  data_array(out, "UInt8", "colour", 3, join(g.colour));
  out << "      </CellData>\n";
  if (!g.vert_offsets.empty()) {
    out << "      <Verts>\n";
    data_array(out, "Int64", "connectivity", 1, join(g.vert_connectivity));
    data_array(out, "Int64", "offsets", 1, join(g.vert_offsets));
    out << "      </Verts>\n";
  }
  if (!g.line_offsets.empty()) {
    out << "      <Lines>\n";
    data_array(out, "Int64", "connectivity", 1, join(g.line_connectivity));
    data_array(out, "Int64", "offsets", 1, join(g.line_offsets));
    out << "      </Lines>\n";
  }
  out << "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  std::ofstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot be written");
  file << out.str();
  if (!file.flush()) throw InputError(path + ": cannot be written (disk full?)");
}

}  // namespace ibfvs
