#pragma once
// The topology as VTK PolyData lays it out, made in this one place for every
// front end: `ibfvs topology` writes it as a .vtp file, ParaView's filter
// copies it into its output, Python hands its arrays to numpy and PyVista.
//
// Points: each critical point, then each line's points in order. Cells: a
// vertex per critical point, then a polyline per line (a closed one ends at
// its first point again). Arrays:
//  - cells: `kind` (1-6 points, 10 separation, 11 attachment), `id` (the
//    feature's, kept from step to step), `strength` (a point's largest
//    absolute real eigenvalue part; a line's FeatureLine::strength),
//    `length` (0 for points), `origin` (0 for points, LineOrigin for
//    lines), `colour` (the kind's sRGB, 3 unsigned chars: shown as it is
//    with ParaView's Map Scalars off);
//  - points: `index` (Poincare index; 0 on lines), `magnitude` (|w|; 0 at
//    critical points), `eigenvalues` (4: real and imaginary part of the
//    first, then the second; a line point's imaginary parts 0), `Normals`
//    (the surface's);
//  - field data: `summary` (one string).

#include <cstdint>
#include <string>
#include <vector>

#include "ibfvs/core/fields/topology.h"

namespace ibfvs {

struct TopologyLayout {
  // ---- per point
  std::vector<float> points;   ///< x y z
  std::vector<float> normals;  ///< x y z
  std::vector<std::int32_t> index;
  std::vector<float> magnitude;
  std::vector<double> eigenvalues;  ///< 4 a point
  // ---- cells: the vertices, then the lines (VTK's offsets, from the first end)
  std::vector<std::int64_t> vert_connectivity, vert_offsets;
  std::vector<std::int64_t> line_connectivity, line_offsets;
  // ---- per cell, vertices first
  std::vector<std::int32_t> kind, id, origin;
  std::vector<double> strength, length;
  std::vector<std::uint8_t> colour;  ///< r g b
  std::string summary;

  [[nodiscard]] std::size_t point_count() const { return points.size() / 3; }
  [[nodiscard]] std::size_t cell_count() const { return kind.size(); }
};

/// The layout of `topology`, with `summary` as its field data.
TopologyLayout topology_layout(const FlowTopology& topology, std::string summary);

/// Writes the layout as VTK XML PolyData (ASCII). Throws InputError naming
/// the file when it cannot be written.
void write_topology_vtp(const TopologyLayout& layout, const std::string& path);

}  // namespace ibfvs
