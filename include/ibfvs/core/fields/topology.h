#pragma once
// The topology of a tangent vector field on a triangle mesh (issue 64): its
// critical points, found and classified as Helman and Hesselink did for flow
// data ("Representation and display of vector field topology in fluid flow
// data sets", IEEE Computer 22(8):27-36, 1989): a critical point is a zero
// of the field, its kind given by the eigenvalues of the field's Jacobian
// there (saddle: real, opposite signs; node: real, one sign; focus:
// complex; centre: imaginary).
// On a surface, the field is the piecewise-linear one: on each triangle, the
// linear interpolation of its corners' vectors (tangent to their vertex
// normals: tangent_vectors) projected into the triangle's plane, which has at most one zero and a
// constant Jacobian. A zero inside a triangle (or on its edges or corners, counted once) is a
// critical point. On a closed surface their indices sum to the Euler
// characteristic (Poincare-Hopf), which the tests check.
//
// Separation and attachment lines: the parallel-vectors form of the
// eigenvector method of Kenwright, Henze and Levit ("Feature extraction of
// separation and attachment lines", IEEE TVCG 5(2):135-144, 1999), as
// Peikert and Roth wrote it ("The parallel vectors operator", IEEE
// Visualization 1999): a line lies where the wall flow w is parallel to an
// eigenvector of its Jacobian J, i.e. where w x Jw = 0; it is a separation
// line where the other eigenvalue is negative and below the first (the
// neighbouring flow converges onto it), an attachment line where it is
// positive and above (it diverges from it). Why this method: it finds open
// separation, which starts at no saddle (the common kind on car bodies,
// wings and fans), and closed separation around a body, which integrating
// separatrices from saddles misses; and it needs only the Jacobian at the
// vertices (the area-weighted mean of the triangles' constant Jacobians,
// tangent to the vertex's normal), so it runs on any triangle mesh in one
// pass. The scalar n . (w x Jw) at the vertices, linear over each triangle,
// gives the lines as its zero contour (no eigenvector orientation to fix,
// unlike w x e); segments are kept where the transverse rate is at least
// `min_strength` of the field's rate and chained across the edges they
// share into polylines of at least `min_length` edges.

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// The kinds of issue 64's `kind` array (1-6: critical points).
enum class CriticalKind : int {
  Saddle = 1,
  AttractingNode = 2,
  RepellingNode = 3,
  AttractingFocus = 4,
  RepellingFocus = 5,
  Centre = 6,
};

/// The name of a kind ("saddle", "attracting node", ...).
const char* kind_name(CriticalKind kind);

struct CriticalPoint {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  ///< its triangle's
  std::size_t triangle = 0;            ///< the triangle it was found in
  CriticalKind kind = CriticalKind::Saddle;
  int index = 1;  ///< Poincare index: -1 for a saddle, +1 otherwise
  /// The Jacobian's eigenvalues, real and imaginary parts (1/time in the
  /// field's units per the mesh's length).
  std::array<double, 2> eigen_real{}, eigen_imag{};
};

struct CriticalPoints {
  std::vector<CriticalPoint> points;
  int index_sum = 0;
  /// Triangles with no area, or whose linear field has no isolated zero
  /// (zero or constant along a line): left out and counted.
  std::size_t degenerate_triangles = 0;
  /// Triangles whose three corner vectors are all zero (no direction there).
  std::size_t zero_triangles = 0;
};

/// `vectors` less their part along each vertex's normal (the area-weighted
/// mean of its triangles'): what both finders below work on, so that a
/// field with a normal part (a near-wall velocity, a vector off a curved
/// wall) has the zeros of its tangent part.
std::vector<glm::vec3> tangent_vectors(const TriMesh& mesh, std::span<const glm::vec3> vectors);

/// The critical points of `vectors` (one per vertex of `mesh`). Throws
/// InputError when the counts differ or a vector or position is not finite.
CriticalPoints find_critical_points(const TriMesh& mesh, std::span<const glm::vec3> vectors);

/// Issue 64's `kind` for lines.
enum class LineKind : int { Separation = 10, Attachment = 11 };

/// "separation line" or "attachment line".
const char* kind_name(LineKind kind);

/// A point on a feature line with the field there.
struct LinePoint {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  ///< the surface's, interpolated
  float magnitude = 0.0f;              ///< |w| (tangent part), interpolated
  std::array<double, 2> eigen{};       ///< J's real eigenvalues there (0, 0: complex)
};

struct FeatureLine {
  LineKind kind = LineKind::Separation;
  std::vector<LinePoint> points;  ///< in order; a closed line repeats no point
  bool closed = false;
  double strength = 0.0;  ///< mean transverse rate along it (1/time, as the eigenvalues)
  double length = 0.0;    ///< in the mesh's units
};

struct LineOptions {
  /// A segment is kept where its transverse rate is at least this fraction
  /// of the field's rate (the area-weighted RMS of the Jacobian's norm).
  double min_strength = 0.1;
  /// A line is kept when it is at least this many mean edges long.
  double min_length = 4.0;
};

struct FeatureLines {
  std::vector<FeatureLine> lines;
  double rate = 0.0;       ///< the field's rate that min_strength is a fraction of
  double mean_edge = 0.0;  ///< the mesh's mean edge length
};

/// The separation and attachment lines of `vectors` (one per vertex of
/// `mesh`). Throws InputError as find_critical_points does.
FeatureLines find_feature_lines(const TriMesh& mesh, std::span<const glm::vec3> vectors,
                                const LineOptions& options = {});

/// How every front end draws a kind: its `kind` value, name and colour
/// (sRGB, 0-255): lines red for separation, blue for attachment; points
/// by kind. The one table the summary, Python and the plugin read.
struct KindStyle {
  int kind;
  const char* name;
  std::array<unsigned char, 3> rgb;
};
std::span<const KindStyle> kind_styles();

/// Both: what `ibfvs topology` and the front ends give.
struct FlowTopology {
  CriticalPoints critical;
  FeatureLines lines;
  [[nodiscard]] std::size_t count(CriticalKind kind) const;
  [[nodiscard]] std::size_t count(LineKind kind) const;
};

FlowTopology find_topology(const TriMesh& mesh, std::span<const glm::vec3> vectors,
                           const LineOptions& options = {});

/// One line: "3 saddles, 2 attracting nodes, ..., 4 separation lines, 1
/// attachment line; index sum 2 (Euler characteristic 2)", with the
/// triangles left out when there are any.
std::string topology_summary(const FlowTopology& topology, const TriMesh& mesh);

/// Writes the topology as VTK XML PolyData (ASCII): a vertex per critical
/// point, a polyline per line; cell array `kind` (1-6, 10, 11) and
/// `strength`, point arrays `index`, `magnitude`, `eigenvalues` (4
/// components: real and imaginary part of the first, then the second) and
/// `Normals` (the surface's there, to lift them off it or orient glyphs).
/// Throws InputError naming the file when it cannot be written.
void write_topology_vtp(const FlowTopology& topology, const std::string& path);

/// Checks `vectors` against `mesh` (counts, finite values): the InputError
/// find_critical_points and find_feature_lines throw.
void check_topology_input(const TriMesh& mesh, std::span<const glm::vec3> vectors);

/// V - E + F of the mesh (edges counted once): 2 for a sphere, 0 for a torus.
long euler_characteristic(const TriMesh& mesh);

}  // namespace ibfvs
