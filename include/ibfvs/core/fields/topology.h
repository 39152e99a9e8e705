#pragma once
// The skin-friction topology of a tangent vector field on a triangle mesh
// (issues 64 and 73): its critical points and its separation and attachment
// lines, as an aerodynamicist reads them off an oil-flow picture.
//
// Critical points (Helman and Hesselink, "Representation and display of
// vector field topology in fluid flow data sets", IEEE Computer 22(8):27-36,
// 1989): the field linear over each triangle (its corners' vectors, tangent
// to their vertex normals, projected into its plane) has at most one zero
// there, classified by the eigenvalues of its Jacobian (saddle: real,
// opposite signs; node: real, one sign; focus: complex; centre:
// imaginary). On a closed surface the indices sum to the Euler
// characteristic (Poincare-Hopf), which the tests check.
//
// Lines are skin-friction lines, found by following the field
// (surface_field.h traces them; only the field's direction enters, so
// scaling each vertex's vector by a positive factor of its own changes no
// line): a separation line is one onto which its neighbours converge, an
// attachment line one from which they diverge (Lighthill, "Attachment and
// separation in three-dimensional flow", 1963; Tobak and Peake, "Topology of
// three-dimensional separated flows", Annu. Rev. Fluid Mech. 14, 1982).
// Four kinds are found (feature_lines.cpp):
//  - separatrices, integrated from the saddles (Helman and Hesselink): the
//    outgoing ones separation lines, the incoming ones attachment lines; a
//    line from one saddle into another (a saddle-to-saddle connection)
//    emanates from the first: a separation line, found once;
//  - closed orbits, the fixed points of a first-return (Poincare) map on an
//    edge that a trace crosses again and again (Wischgoll and Scheuermann,
//    "Detection and visualization of closed streamlines in planar flows",
//    IEEE TVCG 7(2), 2001): attracting ones separation lines, repelling ones
//    attachment lines (Surana, Grunberg and Haller, "Exact theory of
//    three-dimensional flow separation. Part 1. Steady separation", J. Fluid
//    Mech. 564, 2006: separation lines are unstable manifolds of saddles and
//    limit cycles of the wall shear);
//  - open separation and attachment, which start at no saddle: traces from
//    where the field's lines converge (or diverge) strongly and where they
//    run straight (Kenwright, Henze and Levit's eigenvector criterion, "Feature
//    extraction of separation and attachment lines", IEEE TVCG 5(2), 1999, in
//    Peikert and Roth's parallel-vectors form, here only a seed), followed
//    forward (backward for attachment) while their neighbours keep
//    converging onto them: an attracting line draws the trace onto itself;
//  - lines of zeros, where the field vanishes along a curve (2-D and
//    axisymmetric separation): edges whose two ends flow towards each other
//    (or away), chained; separation where the flow on both sides comes in.
//    The critical points that the discrete field scatters along such a
//    line belong to it, not to the points.
// Significance: one scale (a fraction of the surface's size) cancels what a
// user would call noise: a saddle and a node or focus closer than it cancel
// (their indices sum to 0), lines shorter than it are dropped, and a line
// is kept when its neighbours converge onto it (diverge from it) by at
// least e^min_strength along it, measured against the flow's own
// compression along it (an even contraction into a node draws no line).

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

class SurfaceField;

/// The kinds of the `kind` array (1-6: critical points).
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
  /// field's units per the mesh's length), real parts ascending.
  std::array<double, 2> eigen_real{}, eigen_imag{};
  int id = -1;  ///< the feature's id: kept from step to step (carry_ids)
  /// The largest absolute real part of the eigenvalues (the `strength` array).
  [[nodiscard]] double strength() const;
};

struct CriticalPoints {
  std::vector<CriticalPoint> points;
  /// The sum of the kept points' indices (find_topology; every zero's for
  /// find_critical_points): a cancelled pair's sum to 0, and a line of
  /// zeros has index 0 as a whole. On a closed surface, Poincare-Hopf's
  /// Euler characteristic.
  int index_sum = 0;
  /// Triangles with no area, or whose linear field has no isolated zero
  /// (zero or constant along a line): left out and counted.
  std::size_t degenerate_triangles = 0;
  /// Triangles whose three corner vectors are all zero (no direction there).
  std::size_t zero_triangles = 0;
  /// Zeros left out as insignificant: pairs of a saddle and a node, focus
  /// or centre closer than the scale (their indices sum to 0).
  std::size_t cancelled = 0;
  /// Zeros on a line of zeros, part of that line.
  std::size_t on_lines = 0;
};

/// `vectors` less their part along each vertex's normal (the area-weighted
/// mean of its triangles'): what the topology works on, so that a field
/// with a normal part (a near-wall velocity, a vector off a curved wall) has
/// the zeros of its tangent part.
std::vector<glm::vec3> tangent_vectors(const TriMesh& mesh, std::span<const glm::vec3> vectors);

/// Every zero of `vectors` (one per vertex of `mesh`), none left out. Throws
/// InputError when the counts differ or a vector or position is not finite.
CriticalPoints find_critical_points(const TriMesh& mesh, std::span<const glm::vec3> vectors);
CriticalPoints find_critical_points(const SurfaceField& field);

/// The `kind` of a line.
enum class LineKind : int { Separation = 10, Attachment = 11 };

/// "separation line" or "attachment line".
const char* kind_name(LineKind kind);

/// How a line was found (the `origin` array).
enum class LineOrigin : int {
  Separatrix = 1,   ///< from a saddle
  ClosedOrbit = 2,  ///< a limit cycle
  Open = 3,         ///< open separation or attachment: from no saddle
  Zeros = 4,        ///< a line along which the field vanishes
};

/// "separatrix", "closed orbit", "open", "zeros".
const char* origin_name(LineOrigin origin);

/// A point on a feature line with the field there.
struct LinePoint {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  ///< the surface's, interpolated
  float magnitude = 0.0f;              ///< |w| (tangent part), interpolated
  std::array<double, 2> eigen{};  ///< its triangle's Jacobian's real eigenvalues (0, 0: complex)
};

struct FeatureLine {
  LineKind kind = LineKind::Separation;
  LineOrigin origin = LineOrigin::Open;
  std::vector<LinePoint> points;  ///< in the flow's direction; a closed line repeats no point
  bool closed = false;
  /// How strongly its neighbours converge onto it (separation) or diverge
  /// from it (attachment): the natural log of the factor by which their
  /// distance to it shrinks (grows) along it, less the flow's own
  /// compression (stretching) along it. Dimensionless; infinite for a line of zeros.
  double strength = 0.0;
  double length = 0.0;  ///< in the mesh's units
  int id = -1;          ///< the feature's id: kept from step to step (carry_ids)
};

/// What counts as a feature (the significance scale).
struct TopologyOptions {
  /// The scale, as a fraction of the surface's size (its bounding box's
  /// diagonal): a saddle and a node or focus closer than it cancel, and
  /// lines shorter than min_length of it are dropped.
  double scale = 0.03;
  /// A line is kept where its neighbours converge onto it (or diverge) by at
  /// least e^min_strength along it (see FeatureLine::strength).
  double min_strength = 2.0;
  /// A line is kept when it is at least this many scales long.
  double min_length = 2.0;
  bool operator==(const TopologyOptions&) const = default;
};

/// Throws InputError naming the option when one is out of its range
/// (scale in (0, 1], min_strength and min_length not negative, all finite).
void check_topology_options(const TopologyOptions& options);

struct FeatureLines {
  std::vector<FeatureLine> lines;
  double scale = 0.0;      ///< the significance scale in the mesh's units
  double mean_edge = 0.0;  ///< the mesh's mean edge length
};

/// How every front end draws a kind: its `kind` value, name and colour
/// (sRGB, 0-255): lines red for separation, blue for attachment; points
/// by kind. The one table the summary, Python and the plugin read.
struct KindStyle {
  int kind;
  const char* name;
  std::array<unsigned char, 3> rgb;
};
std::span<const KindStyle> kind_styles();
/// The colour of a kind (white for one not in the table).
std::array<unsigned char, 3> kind_colour(int kind);

/// Both: what `ibfvs topology` and the front ends give.
struct FlowTopology {
  CriticalPoints critical;
  FeatureLines lines;
  [[nodiscard]] std::size_t count(CriticalKind kind) const;
  [[nodiscard]] std::size_t count(LineKind kind) const;
};

/// The significant critical points and lines of `vectors` (one per vertex
/// of `mesh`). Throws InputError for bad input (check_topology_input) or
/// options (check_topology_options). Ids number the points, then the lines, from 0.
FlowTopology find_topology(const TriMesh& mesh, std::span<const glm::vec3> vectors,
                           const TopologyOptions& options = {});

/// Ids that last from step to step of a series: each feature of `next`
/// takes the id of the feature of `previous` it continues, a new one
/// (`next_id`, counted up) otherwise. A point continues one of its index
/// (saddles saddles; nodes, foci and centres each other, its own kind first)
/// within `reach`; a line continues one of its kind that it lies along (at
/// least half its points within `reach` of it, the nearest on average; at
/// most 32 of its points are measured).
/// Each feature of `previous` is continued once: where one splits, the
/// nearer part keeps its id; where two merge, the nearer one's id goes on.
/// `reach`: the largest distance a feature moves in a step, in the mesh's
/// units (the front ends use twice the significance scale).
void carry_ids(const FlowTopology& previous, FlowTopology& next, int& next_id, double reach);

/// One line: "3 saddles, 2 attracting nodes, ..., 4 separation lines, 1
/// attachment line; index sum 2 (Euler characteristic 2)", with the
/// triangles left out and the zeros cancelled when there are any.
std::string topology_summary(const FlowTopology& topology, const TriMesh& mesh);

/// Checks `vectors` against `mesh` (counts, finite values): the InputError
/// the topology throws.
void check_topology_input(const TriMesh& mesh, std::span<const glm::vec3> vectors);

/// V - E + F of the mesh (edges counted once): 2 for a sphere, 0 for a torus.
long euler_characteristic(const TriMesh& mesh);

}  // namespace ibfvs
