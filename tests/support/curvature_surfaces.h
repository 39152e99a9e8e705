#pragma once
// Irregular meshes of surfaces whose curvature is known exactly, for the
// curvature tests and bench/curvature_accuracy: jittered tori and ellipsoids
// (vertices moved along the surface), randomly triangulated spheres (the
// convex hull of random points, through CGAL) and Loop subdivision surfaces
// (a coarse mesh refined and moved onto its limit surface, whose curvature
// at regular vertices follows from the control points, Stam 1998).

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/geometry/curvature.h"
#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs::test {

/// A mesh whose vertices lie on a surface, with that surface's curvature.
struct TestSurface {
  std::string name;
  TriMesh mesh;                   ///< normals from compute_vertex_normals, as a file would give
  std::vector<float> kmin, kmax;  ///< exact, signed as Curvature (outward normals)
  std::vector<glm::vec3> dmin, dmax;
  std::vector<std::uint8_t> known;  ///< 1 where the exact values are known and count
  float kappa_rms = 0.0f;           ///< RMS principal curvature over the known vertices
};

/// Torus of radii R, r around y with segments x sides vertices, each moved
/// in the parameter plane by up to `jitter` edges (0: the regular torus).
TestSurface jittered_torus(float R, float r, int segments, int sides, float jitter,
                           std::uint32_t seed);

/// Ellipsoid of semi-axes `radii`: a Loop-refined icosahedron whose vertices
/// are moved along the unit sphere by up to `jitter` edges, then scaled.
TestSurface jittered_ellipsoid(glm::vec3 radii, int level, float jitter, std::uint32_t seed);

/// The convex hull of `points` random points on a sphere of radius r: a
/// random triangulation, with slivers and valences from 3 to 10 or more.
/// Empty (no vertices) where the build has no CGAL.
TestSurface random_sphere(float r, int points, std::uint32_t seed);

/// `coarse` refined by `levels` Loop subdivisions with every vertex moved to
/// its limit position: the curvature is known at vertices whose 3-ring is
/// regular (valence 6, no boundary). `coarse` needs a closed, manifold mesh.
TestSurface loop_limit_surface(const TriMesh& coarse, int levels, const std::string& name);

/// Moves every vertex of `s` along its normal by Gaussian noise whose
/// standard deviation is `fraction` of the mean edge length (a scan's noise);
/// the exact values stay those of the smooth surface.
void add_normal_noise(TestSurface& s, float fraction, std::uint32_t seed);

/// Errors of `c` on the known vertices of `s`.
struct CurvatureErrors {
  std::size_t count = 0;                         ///< vertices measured
  double kmax_rel_median = 0, kmax_rel_p95 = 0;  ///< |dkmax| / max(|kmax|, kappa_rms)
  double kmin_abs_median = 0, kmin_abs_p95 = 0;  ///< |dkmin|
  double dir_median = 0, dir_p95 = 0;  ///< degrees, dmax, where kmax - kmin > kappa_rms / 10
  std::size_t non_finite = 0;          ///< NaN or infinite outputs (anywhere)
};
CurvatureErrors curvature_errors(const TestSurface& s, const Curvature& c);

/// True when the build could make random_sphere (CGAL found).
bool have_cgal();

/// CGAL's Monge jet fitting (Cazals and Pouget 2005) at every vertex: a jet
/// of `degree` fitted to the vertex and its `rings`-ring (grown while it has
/// fewer points than the jet's coefficients), signs and normals made to
/// agree with the mesh's. The peer the accuracy table compares with; empty
/// where the build has no CGAL.
Curvature cgal_jet_fitting(const TriMesh& mesh, int degree, int rings);

}  // namespace ibfvs::test
