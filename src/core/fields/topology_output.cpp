// The topology's summary line and its VTK XML PolyData file (topology.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "ibfvs/core/fields/topology.h"
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
  if (t.critical.zero_triangles > 0)
    s += "; the field is zero on " + std::to_string(t.critical.zero_triangles) + " triangles";
  if (t.critical.degenerate_triangles > 0)
    s += "; " + std::to_string(t.critical.degenerate_triangles) +
         " triangles without an isolated zero or area left out";
  return s;
}

void write_topology_vtp(const FlowTopology& t, const std::string& path) {
  std::ostringstream xyz, normal, index, magnitude, eigen, kind, strength, vconn, voff, lconn, loff;
  auto number = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.9g ", v);
    return std::string(b);
  };
  std::size_t id = 0;
  for (const CriticalPoint& p : t.critical.points) {
    xyz << number(p.position.x) << number(p.position.y) << number(p.position.z);
    normal << number(p.normal.x) << number(p.normal.y) << number(p.normal.z);
    index << p.index << ' ';
    magnitude << "0 ";
    eigen << number(p.eigen_real[0]) << number(p.eigen_imag[0]) << number(p.eigen_real[1])
          << number(p.eigen_imag[1]);
    kind << static_cast<int>(p.kind) << ' ';
    strength << number(std::max(std::abs(p.eigen_real[0]), std::abs(p.eigen_real[1])));
    vconn << id++ << ' ';
    voff << id << ' ';
  }
  std::size_t line_end = 0;
  for (const FeatureLine& l : t.lines.lines) {
    const std::size_t first = id;
    for (const LinePoint& p : l.points) {
      xyz << number(p.position.x) << number(p.position.y) << number(p.position.z);
      normal << number(p.normal.x) << number(p.normal.y) << number(p.normal.z);
      index << "0 ";
      magnitude << number(p.magnitude);
      eigen << number(p.eigen[0]) << "0 " << number(p.eigen[1]) << "0 ";
      lconn << id++ << ' ';
    }
    if (l.closed) lconn << first << ' ';
    line_end += l.points.size() + (l.closed ? 1 : 0);
    loff << line_end << ' ';
    kind << static_cast<int>(l.kind) << ' ';
    strength << number(l.strength);
  }
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << id << "\" NumberOfVerts=\"" << t.critical.points.size()
      << "\" NumberOfLines=\"" << t.lines.lines.size()
      << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  out << "      <Points>\n";
  data_array(out, "Float32", "Points", 3, xyz.str());
  out << "      </Points>\n      <PointData Scalars=\"index\" Normals=\"Normals\">\n";
  data_array(out, "Int32", "index", 1, index.str());
  data_array(out, "Float32", "magnitude", 1, magnitude.str());
  data_array(out, "Float64", "eigenvalues", 4, eigen.str());
  data_array(out, "Float32", "Normals", 3, normal.str());
  out << "      </PointData>\n      <CellData Scalars=\"kind\">\n";
  data_array(out, "Int32", "kind", 1, kind.str());
  data_array(out, "Float64", "strength", 1, strength.str());
  out << "      </CellData>\n";
  if (!t.critical.points.empty()) {
    out << "      <Verts>\n";
    data_array(out, "Int64", "connectivity", 1, vconn.str());
    data_array(out, "Int64", "offsets", 1, voff.str());
    out << "      </Verts>\n";
  }
  if (!t.lines.lines.empty()) {
    out << "      <Lines>\n";
    data_array(out, "Int64", "connectivity", 1, lconn.str());
    data_array(out, "Int64", "offsets", 1, loff.str());
    out << "      </Lines>\n";
  }
  out << "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  std::ofstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot be written");
  file << out.str();
  if (!file.flush()) throw InputError(path + ": cannot be written (disk full?)");
}

}  // namespace ibfvs
