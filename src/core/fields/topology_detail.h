#pragma once
// The topology's lines as they are found, before their LinePoints
// (topology.h): shared by the zero lines (zero_lines.cpp) and the traced
// lines (feature_lines.cpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/fields/surface_field.h"
#include "ibfvs/core/fields/topology.h"

namespace ibfvs::detail {

/// Lengths the finder works with, from the options and the mesh.
struct Scales {
  double scale = 0.0;       ///< the significance scale (options.scale x the size)
  double fine = 0.0;        ///< the finder's own resolution (a fiftieth of the size)
  double merge = 0.0;       ///< a trace this close to a line has joined it
  double seed_gap = 0.0;    ///< no seed this close to a line of its kind
  double disk = 0.0;        ///< a trace this close to a kept critical point ends there
  double connect = 0.0;     ///< a separatrix turning this close to a saddle connects to it
  double step = 0.0;        ///< the longest tracing step
  double max_length = 0.0;  ///< the longest trace
  double min_length = 0.0;  ///< the shortest line kept
};

Scales scales_of(const SurfaceField& field, const TopologyOptions& options);

/// A line as found: points with their triangles, in the flow's direction.
struct RawLine {
  LineKind kind = LineKind::Separation;
  LineOrigin origin = LineOrigin::Open;
  bool closed = false;
  std::vector<TracePoint> points;
  double strength = 0.0;
  /// An open line's length traced against its sense from its seed (its
  /// extension upstream, the less accurate part: a trace that joins it
  /// there takes its place).
  double extension = 0.0;
  double seed_rate = 0.0;  ///< the convergence rate at its seed
  /// The critical points it starts and ends at (indices of the kept ones).
  std::optional<std::uint32_t> from_point, to_point;
};

/// The largest strength a line is given: its neighbours reach it (a line
/// of zeros) or converge past any measure (e^50).
inline constexpr double kFullStrength = 50.0;

/// The lines along which the field vanishes: chains of edges whose two ends'
/// directions are nearly opposite and point towards each other (separation)
/// or away (attachment), through the points where the cross-flow is zero.
/// Only lines at least `scales.min_length` long.
std::vector<RawLine> find_zero_lines(const SurfaceField& field, const Scales& scales);

/// A uniform grid of points for "what is near": cell `cell` wide.
class PointGrid {
 public:
  /// Cells in a hash map: any extent.
  explicit PointGrid(double cell) : cell_(cell > 0.0 ? cell : 1.0) {}
  /// Cells in an array over the box lo..hi (a point outside goes to the
  /// nearest cell), where that takes at most 4 million cells; else as above.
  PointGrid(double cell, const glm::dvec3& lo, const glm::dvec3& hi);
  void insert(const glm::dvec3& p, std::uint32_t item);
  /// Calls visit(item) for every item in the cells that the cube of half
  /// width `radius` (at most the cell's width) about p meets: 8 at most. A
  /// visit that returns bool stops the search by returning true; near then
  /// returns true.
  template <class Visit>
  bool near(const glm::dvec3& p, double radius, Visit visit) const {
    const auto call = [&](std::uint32_t item) {
      if constexpr (std::is_same_v<std::invoke_result_t<Visit&, std::uint32_t>, bool>) {
        return visit(item);
      } else {
        visit(item);
        return false;
      }
    };
    const Cell lo = cell_of(p - glm::dvec3(radius)), hi = cell_of(p + glm::dvec3(radius));
    for (std::int64_t x = lo.x; x <= hi.x; ++x)
      for (std::int64_t y = lo.y; y <= hi.y; ++y)
        for (std::int64_t z = lo.z; z <= hi.z; ++z) {
          const std::vector<std::uint32_t>* items = nullptr;
          if (!dense_.empty()) {
            items = &dense_[static_cast<std::size_t>((z * dims_[1] + y) * dims_[0] + x)];
          } else if (const auto it = cells_.find(key(x, y, z)); it != cells_.end()) {
            items = &it->second;
          }
          if (items)
            for (const std::uint32_t item : *items)
              if (call(item)) return true;
        }
    return false;
  }
  /// The same within the cell's width.
  template <class Visit>
  bool near(const glm::dvec3& p, Visit visit) const {
    return near(p, cell_, visit);
  }
  [[nodiscard]] double cell() const { return cell_; }
  /// The key of p's cell (unique within about 2 million cells an axis).
  [[nodiscard]] std::uint64_t key_of(const glm::dvec3& p) const {
    const Cell c = cell_of(p);
    return key(c.x, c.y, c.z);
  }

 private:
  struct Cell {
    std::int64_t x, y, z;
  };
  [[nodiscard]] Cell cell_of(const glm::dvec3& p) const {
    if (!dense_.empty()) {
      const auto c = [&](int k) {
        const double v = std::floor((p[k] - origin_[k]) / cell_);
        return static_cast<std::int64_t>(std::clamp(v, 0.0, static_cast<double>(dims_[k] - 1)));
      };
      return {c(0), c(1), c(2)};
    }
    const auto c = [&](double v) {
      return static_cast<std::int64_t>(std::clamp(std::floor(v / cell_), -1e15, 1e15));
    };
    return {c(p.x), c(p.y), c(p.z)};
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    const auto m = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & 0x1fffff; };
    return m(x) << 42 | m(y) << 21 | m(z);
  }
  double cell_;
  glm::dvec3 origin_{0.0};
  std::int64_t dims_[3] = {0, 0, 0};
  std::vector<std::vector<std::uint32_t>> dense_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace ibfvs::detail
