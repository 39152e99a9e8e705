#pragma once
// Principal curvatures and directions per vertex, as the IBFVS paper needs
// them after reading a mesh (section 5), by local polynomial fits:
//
// - the quartic jet of F. Cazals and M. Pouget, "Estimating differential
//   quantities using polynomial fitting of osculating jets", Computer Aided
//   Geometric Design 22(2), 2005 (CGAL's Monge_via_jet_fitting): at each
//   vertex p, z = sum c_ij x^i y^j (1 <= i + j <= 4, through p) is fitted by
//   least squares to the 2-ring in the frame of the mesh normal, near
//   neighbours weighted more (a Gaussian of half a mean neighbour distance);
//   the exact curvature of the fitted graph at p, whatever its tilt, gives
//   the normal, principal curvatures and directions. Errors fall as h^3 on
//   any triangulation; noise, though, it follows.
// - the cubic fit of J. Goldfeather and V. Interrante, "A novel cubic-order
//   algorithm for approximating principal direction vectors", ACM
//   Transactions on Graphics 23(1), 2004 (the one the IBFVS paper used): a
//   cubic fitted to the 2-ring's positions and normals (two slope equations
//   each), the normals those of a first cubic fit of positions. Biased as
//   h^2, but three equations per neighbour average a scan's noise.
//
// By default each mesh gets the one that suits it (CurvatureFit::automatic):
// on exact surfaces the two differ by the cubic's bias, many times the
// quartic's standard error estimated from its residuals; on noisy ones by a
// few times only. Measured against CGAL on the same meshes:
// bench/curvature_accuracy.cpp and docs/geometry.md.

#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// How compute_curvature fits each vertex.
enum class CurvatureFit {
  /// The quartic on exact meshes (CAD, subdivision and simulation
  /// surfaces), the cubic with normals on noisy ones (scans): where the two
  /// differ, over a sample of vertices, by less than 6 times the quartic's
  /// standard error (estimated from its residuals), noise dominates.
  automatic,
  /// A jet of degree 4 fitted to the positions of the 2-ring (Cazals and
  /// Pouget 2005): errors fall as h^3 on any triangulation, but it follows
  /// noise.
  quartic,
  /// A cubic fitted to positions and normals (Goldfeather and Interrante
  /// 2004), with normals from a first cubic fit of positions: errors fall
  /// as h^2 only, but noise of a scan averages out.
  cubic_with_normals,
};

/// Options of compute_curvature.
struct CurvatureOptions {
  CurvatureFit fit = CurvatureFit::automatic;
  /// Rings of neighbours fitted, 1 to 3; grown (up to 3) while there are
  /// fewer than 17 vertices (the quartic's 14 coefficients and 3 more).
  int rings = 2;
  /// Width of the quartic's Gaussian weights, in mean neighbour distances
  /// (0: equal weights): near neighbours count more, where the jet's
  /// truncation error is smallest.
  float weight_radius = 0.5f;
  /// Neighbour normals tilted more than this from the vertex normal (cosine)
  /// give no slope equations: across a crease they say nothing about the fit.
  float min_normal_cosine = 0.3f;
};

/// Per-vertex curvature. Signs follow the normals: a sphere with outward
/// normals has kmin = kmax = 1/r > 0; a saddle has kmin < 0 < kmax.
struct Curvature {
  std::vector<float> kmin;        ///< smaller principal curvature
  std::vector<float> kmax;        ///< larger principal curvature
  std::vector<glm::vec3> dmin;    ///< unit direction of kmin, tangent
  std::vector<glm::vec3> dmax;    ///< unit direction of kmax, tangent, orthogonal to dmin
  std::vector<glm::vec3> normal;  ///< refined unit normal (dmax x dmin)
  std::size_t fallback_vertices =
      0;                             ///< vertices fitted by a lower degree than asked, or left flat
  std::size_t quartic_vertices = 0;  ///< vertices whose estimate is the quartic's
  /// The fit used (quartic or cubic_with_normals) and, when it was chosen
  /// automatically, the median ratio that chose it (see CurvatureFit).
  CurvatureFit fit = CurvatureFit::automatic;
  float noise_ratio = 0.0f;
};

/// Curvature of every vertex. Needs `mesh.normals` (compute_vertex_normals).
/// Where the quartic does not fit (too few neighbours, all on a line) or
/// tilts more than 10 degrees from the first cubic's normal (a crease, a thin
/// part), the cubic with normals is used; where that fails, lower degrees,
/// then zero curvature with tangent directions of the frame. Coincident and
/// non-finite neighbours are skipped; no output is ever NaN. Uses every core
/// (OpenMP). Throws InputError when the mesh has no normals.
Curvature compute_curvature(const TriMesh& mesh, const CurvatureOptions& options = {});

/// Copies `c` into the mesh as scalars kmin kmax dminx dminy dminz dmaxx
/// dmaxy dmaxz (the names `ibfvs geometry` writes to PLY) and, when
/// `refined_normals`, its normals into `normals`.
void store_curvature(TriMesh& mesh, const Curvature& c, bool refined_normals = true);

/// The curvature stored in the mesh's scalars (from store_curvature or a PLY
/// written by `ibfvs geometry`, normals from `mesh.normals`), or computed
/// when they are missing: every user reads it through here, so it is
/// computed at most once per mesh.
Curvature mesh_curvature(const TriMesh& mesh);

/// Smooths a tangent line field (unit directions whose sign means nothing,
/// such as Curvature::dmin) over the mesh: each of `iterations` rounds
/// replaces a vertex's direction by the sum of its own and its edge
/// neighbours' directions, each flipped to agree with it, projected on the
/// tangent plane of `normals` and normalised. Restless principal directions of
/// scanned meshes become coherent over about sqrt(iterations) edges; a
/// direction that the neighbours cancel keeps its old value.
std::vector<glm::vec3> smooth_line_field(const TriMesh& mesh, const std::vector<glm::vec3>& normals,
                                         std::vector<glm::vec3> directions, int iterations);

}  // namespace ibfvs
