#pragma once
// The CPU triangle mesh every other part of ibfvs works on: flat arrays that
// map one to one onto GPU vertex and index buffers.

#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace ibfvs {

using Triangle = std::array<std::uint32_t, 3>;

/// A triangle mesh with optional per-vertex data.
struct TriMesh {
  std::vector<glm::vec3> positions;  ///< one per vertex
  std::vector<glm::vec3> normals;    ///< unit, one per vertex (empty until computed)
  std::vector<Triangle> triangles;   ///< counter-clockwise vertex indices
  std::vector<glm::vec3> vectors;    ///< per-vertex vector field from the file (may be empty)
  std::map<std::string, std::vector<float>> scalars;  ///< other per-vertex properties by name
  /// Named per-vertex 3-vectors (VTK and OpenFOAM arrays such as
  /// wallShearStress or U); `field file:NAME` picks one.
  std::map<std::string, std::vector<glm::vec3>> vector_arrays;
  /// Arrays of neither 1 nor 3 components, by name: their component count,
  /// for messages that say why they cannot be a field or a colour.
  std::map<std::string, int> other_arrays;

  [[nodiscard]] std::size_t vertex_count() const { return positions.size(); }
  [[nodiscard]] std::size_t triangle_count() const { return triangles.size(); }
};

/// Axis-aligned bounding box.
struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
  float radius = 0.0f;  ///< largest distance of a vertex from centre() (0: unknown, use diagonal/2)
  [[nodiscard]] glm::vec3 centre() const { return 0.5f * (min + max); }
  [[nodiscard]] float diagonal() const;
};

/// Bounding box of the vertices that some triangle references (unreferenced
/// vertices do not move the camera), with the radius of the sphere about its
/// centre that holds them (what a camera must fit, whatever its direction). Throws InputError for a
/// mesh without triangles.
Bounds mesh_bounds(const TriMesh& mesh);

/// Angle-weighted vertex normals (Thuermer and Wuethrich). Degenerate
/// triangles contribute nothing; a vertex with no valid triangle gets +Z.
void compute_vertex_normals(TriMesh& mesh);

/// Checks the invariants the renderer relies on: indices in range, finite
/// coordinates, per-vertex arrays of the right length. Throws InputError
/// whose message starts with `source`.
void validate_mesh(const TriMesh& mesh, const std::string& source);

/// Per-triangle values carried to the vertices: each vertex gets the
/// area-weighted mean of the values of its triangles (a vertex of no
/// triangle with non-zero area gets the plain mean, or zero). `values` has
/// one entry per triangle; throws InputError otherwise.
std::vector<float> triangle_to_vertex(const TriMesh& mesh, const std::vector<float>& values);
std::vector<glm::vec3> triangle_to_vertex(const TriMesh& mesh,
                                          const std::vector<glm::vec3>& values);

/// Appends `more` to `into`: its vertices after into's, its triangles
/// renumbered to them. A per-vertex array (normals, vectors, a named scalar
/// or vector) stays where both have it, or `into` had no vertices; one that
/// either lacks is dropped, so every array stays one per vertex.
void append_mesh(TriMesh& into, const TriMesh& more);

/// Drops triangles with a repeated vertex index or (`by_area`) zero area;
/// returns how many. Without `by_area`: a later state of a surface whose
/// polygons split as the first state's did (core/mesh/polygon.h), which left
/// out what had no area then; it keeps the first state's triangles.
std::size_t remove_degenerate_triangles(TriMesh& mesh, bool by_area = true);

/// Whether `b` is `a`'s surface with other triangles: as many points, and
/// at least half of b's edges among a's, so that point i of one is point i
/// of the other (the same ids) -- cells split otherwise at a moving mesh's
/// step (a polygon keeps its own edges), or a host's triangles of its own,
/// not another mesh that happens to have as many points. Its points then
/// move along their fitted motion and carry the texture (render/session.h).
/// True for equal triangles.
bool points_correspond(const TriMesh& a, const TriMesh& b);

/// Whether at least half of b's edges are a's (each counted once): the
/// test of points_correspond, for triangles of the same points.
bool most_edges_shared(std::span<const Triangle> a, std::span<const Triangle> b);

/// A 64-bit digest of the vertex count and the triangles, in their order:
/// equal for two states of one surface whose points moved (a time step of a
/// moving mesh), different where the connectivity changed.
std::uint64_t topology_hash(const TriMesh& mesh);

/// Edge and vertex counts that say whether a mesh is closed and manifold.
struct Topology {
  std::size_t edges = 0;              ///< distinct undirected edges
  std::size_t boundary_edges = 0;     ///< edges of one triangle
  std::size_t boundary_loops = 0;     ///< connected chains of boundary edges
  std::size_t nonmanifold_edges = 0;  ///< edges of three or more triangles
  std::size_t isolated_vertices = 0;  ///< vertices of no triangle
};

/// Counts edges, boundary loops, non-manifold edges and isolated vertices.
Topology analyze_topology(const TriMesh& mesh);

/// For a closed, consistently oriented mesh (every directed edge a->b
/// matched by exactly one b->a): +1 when its triangles wind counter-clockwise
/// seen from outside (positive volume), -1 when clockwise; 0 for any other
/// mesh (open, non-manifold, inconsistent). Back faces of such a mesh are
/// always hidden, so the renderer may cull them.
int closed_orientation(const TriMesh& mesh);

}  // namespace ibfvs
