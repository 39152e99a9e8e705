#pragma once
// The per-vertex scalars a scene names (color_by, beta_by, displace): an
// array of the mesh, or one derived from the surface and its field.

#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// A per-vertex scalar by name: a property of the mesh (PLY scalar, kmin and
/// kmax after `ibfvs geometry`, a landscape's height), or one derived here:
/// `speed` (|v| of `field`), `kmin`/`kmax` (computed when absent), `x`, `y`,
/// `z` (coordinates), the magnitude of a named vector array (wallShearStress,
/// U). A leading '-' negates (`-kmax`: concavity). Throws
/// InputError listing the names available.
std::vector<float> vertex_scalar(const TriMesh& mesh, const std::vector<glm::vec3>& field,
                                 std::string_view name);

}  // namespace ibfvs
