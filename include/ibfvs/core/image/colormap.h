#pragma once
// Colour maps for scalars on the surface (paper section 3.3, step 7: "a
// texture mapped mesh can be used, with color representing some scalar
// value"), and per-vertex scalars by name.

#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/support/names.h"

namespace ibfvs {

/// Perceptually uniform maps from their published tables (scripts/gen_colormaps.py).
enum class ColorMap {
  Viridis,   ///< sequential (Smith and van der Walt)
  CoolWarm,  ///< diverging, blue - grey - red (Moreland 2009)
  Grey,      ///< black to white
  Bronze,    ///< dark patina to polished bronze (our palette, for the bronze style)
};

template <>
struct EnumNames<ColorMap> {
  static constexpr EnumName<ColorMap> table[] = {
      {ColorMap::Viridis, "viridis", "sequential, perceptually uniform"},
      {ColorMap::CoolWarm, "coolwarm", "diverging, blue - grey - red"},
      {ColorMap::CoolWarm, "diverging", ""},
      {ColorMap::Grey, "grey", "black to white"},
      {ColorMap::Grey, "gray", ""},
      {ColorMap::Bronze, "bronze", "dark patina to polished bronze"},
  };
};

/// The colour at t in [0, 1] (clamped), interpolated linearly in the table.
glm::vec3 color_map(ColorMap map, float t);

/// Positions in a host's colour table (ParaView's, VTK's) for `values`
/// mapped over the range [lo, hi] as the host maps them: linear, or with
/// `log` the base-10 logarithm (values at or below 0 at lo), clamped to
/// [0, 1]. NaN stays NaN (the host's NaN colour); a range of zero width
/// maps everything to 0.
std::vector<float> table_positions(const std::vector<float>& values, double lo, double hi,
                                   bool log);

/// The range from the `lo` to the `hi` quantile of the finite values
/// (1st and 99th percentile by default), widened when it is empty.
glm::vec2 quantile_range(const std::vector<float>& values, float lo = 0.01f, float hi = 0.99f);

}  // namespace ibfvs
