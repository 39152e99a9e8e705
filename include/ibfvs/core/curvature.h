#pragma once
// Principal curvatures and directions per vertex by the cubic-order fit of
// Goldfeather and Interrante ("A novel cubic-order algorithm for approximating
// principal direction vectors", ACM Transactions on Graphics 23(1), 2004), as
// the IBFVS paper does after reading a mesh (section 5).
//
// At each vertex p with normal n, the neighbours are written in a local frame
// (u, v, n) and a surface z = A/2 x^2 + B xy + C/2 y^2 + D x^3 + E x^2 y + F x y^2 + G y^3
// is fitted by least squares to their positions and to their normals (each
// normal gives two slope equations). The Weingarten matrix [[A, B], [B, C]]
// gives the curvatures (its eigenvalues) and directions (its eigenvectors).
// A first fit with linear terms tilts the normal (the refined normal); the
// cubic fit is then made in the refined frame.

#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/mesh.h"

namespace ibfvs {

/// Options of compute_curvature.
struct CurvatureOptions {
  /// Fewer 1-ring neighbours than this: the 2-ring is used as well.
  int min_neighbours = 5;
  /// Neighbour normals tilted more than this from the vertex normal (cosine)
  /// give no slope equations: across a crease they say nothing about the fit.
  float min_normal_cosine = 0.3f;
  /// Refine the vertex normal with a first fit that has linear terms.
  bool refine_normals = true;
};

/// Per-vertex curvature. Signs follow the normals: a sphere with outward
/// normals has kmin = kmax = 1/r > 0; a saddle has kmin < 0 < kmax.
struct Curvature {
  std::vector<float> kmin;            ///< smaller principal curvature
  std::vector<float> kmax;            ///< larger principal curvature
  std::vector<glm::vec3> dmin;        ///< unit direction of kmin, tangent
  std::vector<glm::vec3> dmax;        ///< unit direction of kmax, tangent, orthogonal to dmin
  std::vector<glm::vec3> normal;      ///< refined unit normal (dmax x dmin)
  std::size_t fallback_vertices = 0;  ///< vertices fitted by the quadratic fallback or left flat
};

/// Curvature of every vertex. Needs `mesh.normals` (compute_vertex_normals).
/// Vertices with too few usable neighbours fall back to a quadratic fit of
/// positions, or to zero curvature with arbitrary tangent directions; no
/// output is ever NaN. Uses every core (OpenMP). Throws InputError when the
/// mesh has no normals.
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
