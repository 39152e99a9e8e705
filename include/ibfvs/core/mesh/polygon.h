#pragma once
// Polygons (a file's faces of five points or more: OpenFOAM's cut cells, a
// polyhedral mesh's faces) as triangles that depend on the polygon's points
// and their order only, not on where the polygon is: the same face of a
// moving mesh gives the same triangles at every time step, so that the
// steps are one surface whose points move (VTK's triangle filter chooses
// its ears by their shape, and the rounding of a moved point flips its
// choice between equal ones).

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// The polygon through `points[ids[0]], points[ids[1]], ...` as triangles
/// of the same winding (ids.size() - 2 of them): a fan from its first point
/// where it is convex (seen along its mean normal, corners turning back by
/// less than 1e-4 of their edges taken as straight), else ear clipping in
/// the order of its points (each ear the first one found from the last).
/// A polygon that is not simple (no ear left) is fanned from there on, and
/// so is one of over 1,024 points (ear clipping's time grows as the cube).
/// Indices must be within `points`.
std::vector<Triangle> triangulate_polygon(std::span<const std::uint32_t> ids,
                                          std::span<const glm::vec3> points);

}  // namespace ibfvs
