#include "ibfvs/core/fields/lonlat_grid.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/mesh/subdivision.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Index i and weight t with x between axis[i] and axis[i + 1] (axis monotonic).
void bracket(const std::vector<double>& axis, double x, std::size_t& i, double& t) {
  const bool up = axis.back() >= axis.front();
  const auto it = up ? std::upper_bound(axis.begin(), axis.end(), x)
                     : std::upper_bound(axis.begin(), axis.end(), x, std::greater<>());
  const std::size_t k = static_cast<std::size_t>(it - axis.begin());
  i = std::clamp<std::size_t>(k == 0 ? 0 : k - 1, 0, axis.size() - 2);
  t = std::clamp((x - axis[i]) / (axis[i + 1] - axis[i]), 0.0, 1.0);
}

}  // namespace

float LonLatGrid::sample(double lon_deg, double lat_deg) const {
  const std::size_t nx = lon.size(), ny = lat.size();
  if (nx < 2 || ny < 2) return std::numeric_limits<float>::quiet_NaN();
  // Longitude: bring into [lon0, lon0 + 360) and wrap between the last and
  // first column when the grid covers the globe.
  const double lon0 = lon.front();
  double x = std::fmod(lon_deg - lon0, 360.0);
  if (x < 0) x += 360.0;
  x += lon0;
  const double step = (lon.back() - lon.front()) / static_cast<double>(nx - 1);
  std::size_t i0 = 0, i1 = 0;
  double tx = 0;
  if (x > lon.back()) {
    const double gap = lon0 + 360.0 - lon.back();
    if (gap > 1.5 * step) return std::numeric_limits<float>::quiet_NaN();  // not global
    i0 = nx - 1, i1 = 0;
    tx = (x - lon.back()) / gap;
  } else {
    bracket(lon, x, i0, tx);
    i1 = i0 + 1;
  }
  std::size_t j0 = 0;
  double ty = 0;
  bracket(lat, lat_deg, j0, ty);
  const auto at = [&](std::size_t j, std::size_t i) {
    return static_cast<double>(values[j * nx + i]);
  };
  const double v = (1 - ty) * ((1 - tx) * at(j0, i0) + tx * at(j0, i1)) +
                   ty * ((1 - tx) * at(j0 + 1, i0) + tx * at(j0 + 1, i1));
  return static_cast<float>(v);  // NaN propagates from any missing neighbour
}

TriMesh make_globe(int level) {
  if (level < 0 || level > 8) throw InputError("globe: the level must be between 0 and 8");
  TriMesh m = loop_subdivide(make_icosahedron(1.0f), level);
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    m.normals[i] = glm::normalize(m.positions[i]);
    m.positions[i] = m.normals[i];
  }
  return m;
}

void to_lonlat(const glm::vec3& p, double& lon_deg, double& lat_deg) {
  const glm::dvec3 d = glm::normalize(glm::dvec3(p));
  lat_deg = std::asin(std::clamp(d.y, -1.0, 1.0)) / kDeg;
  lon_deg = std::atan2(d.x, d.z) / kDeg;
}

std::vector<glm::vec3> lonlat_vectors(const TriMesh& globe, const LonLatGrid& east,
                                      const LonLatGrid& north, std::vector<float>* valid) {
  if (east.lon != north.lon || east.lat != north.lat)
    throw InputError("'" + east.name + "' and '" + north.name +
                     "' are on different grids (mismatched dimensions)");
  std::vector<glm::vec3> out(globe.vertex_count(), glm::vec3(0.0f));
  if (valid) valid->assign(out.size(), 1.0f);
  for (std::size_t i = 0; i < out.size(); ++i) {
    double lon = 0, lat = 0;
    to_lonlat(globe.positions[i], lon, lat);
    const float u = east.sample(lon, lat), v = north.sample(lon, lat);
    if (!std::isfinite(u) || !std::isfinite(v)) {
      if (valid) (*valid)[i] = 0.0f;
      continue;
    }
    const double l = lon * kDeg, p = lat * kDeg;
    const glm::dvec3 e(std::cos(l), 0.0, -std::sin(l));
    const glm::dvec3 n(-std::sin(p) * std::sin(l), std::cos(p), -std::sin(p) * std::cos(l));
    out[i] = glm::vec3(static_cast<double>(u) * e + static_cast<double>(v) * n);
  }
  return out;
}

std::vector<float> lonlat_scalars(const TriMesh& globe, const LonLatGrid& grid) {
  std::vector<float> out(globe.vertex_count());
  for (std::size_t i = 0; i < out.size(); ++i) {
    double lon = 0, lat = 0;
    to_lonlat(globe.positions[i], lon, lat);
    out[i] = grid.sample(lon, lat);
  }
  return out;
}

}  // namespace ibfvs