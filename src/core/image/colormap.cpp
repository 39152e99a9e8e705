#include "ibfvs/core/image/colormap.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

#include "colormap_tables.inc"

}  // namespace

glm::vec3 color_map(ColorMap map, float t) {
  t = std::isfinite(t) ? std::clamp(t, 0.0f, 1.0f) : 0.0f;
  if (map == ColorMap::Grey) return glm::vec3(t);
  if (map == ColorMap::Bronze) {
    // Patina in the hollows, polished metal on the ridges: piecewise linear.
    // Most of a surface lies mid-range: keep that a warm bronze, not patina.
    static constexpr float stops[4][4] = {{0.0f, 0.22f, 0.26f, 0.19f},
                                          {0.3f, 0.52f, 0.38f, 0.20f},
                                          {0.65f, 0.78f, 0.57f, 0.30f},
                                          {1.0f, 0.98f, 0.86f, 0.60f}};
    int k = 0;
    while (k < 2 && t > stops[k + 1][0]) ++k;
    const float f = (t - stops[k][0]) / (stops[k + 1][0] - stops[k][0]);
    return glm::mix(glm::vec3(stops[k][1], stops[k][2], stops[k][3]),
                    glm::vec3(stops[k + 1][1], stops[k + 1][2], stops[k + 1][3]), f);
  }
  const float(*table)[3] = map == ColorMap::Viridis ? kViridis : kCoolWarm;
  const float x = t * 255.0f;
  const int i = std::min(static_cast<int>(x), 254);
  const float f = x - static_cast<float>(i);
  const glm::vec3 a(table[i][0], table[i][1], table[i][2]);
  const glm::vec3 b(table[i + 1][0], table[i + 1][1], table[i + 1][2]);
  return a + f * (b - a);
}

glm::vec2 quantile_range(const std::vector<float>& values, float lo, float hi) {
  std::vector<float> v;
  v.reserve(values.size());
  for (const float x : values)
    if (std::isfinite(x)) v.push_back(x);
  if (v.empty()) return {0.0f, 1.0f};
  const auto at = [&](float q) {
    const auto k = static_cast<std::size_t>(q * static_cast<float>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
  };
  glm::vec2 r(at(lo), at(hi));
  if (!(r.y > r.x)) r = {r.x - 0.5f, r.x + 0.5f};
  return r;
}

std::vector<float> table_positions(const std::vector<float>& values, double lo, double hi,
                                   bool log) {
  log = log && lo > 0.0 && hi > 0.0;
  const auto f = [log](double x) { return log ? std::log10(x) : x; };
  const double a = f(lo), b = f(hi);
  const double span = b > a ? b - a : 1.0;
  std::vector<float> t(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::isnan(values[i])) {
      t[i] = values[i];
      continue;
    }
    const double x = log && values[i] <= 0.0f ? a : f(values[i]);
    const double u = (x - a) / span;
    t[i] = std::isfinite(u) ? static_cast<float>(std::clamp(u, 0.0, 1.0)) : 0.0f;
  }
  return t;
}

}  // namespace ibfvs
