#pragma once
// Shared test helpers: temporary folders, small files written on the fly, and
// statistics on images. Procedural meshes live in ibfvs/core/mesh/procedural.h.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ibfvs/core/image/image.h"

namespace ibfvs::test {

/// A fresh folder under the system temp folder, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("ibfvs-test-" + std::to_string(rd()) + "-" + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const {
    return path_ / name;
  }

 private:
  std::filesystem::path path_;
};

/// Writes `text` (or bytes) to `path` and returns the path.
inline std::filesystem::path write_file(const std::filesystem::path& path,
                                        const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  return path;
}

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Pearson correlation of two equally long sequences over the entries where
/// `mask` is non-zero (NaN if fewer than two entries or no variance).
inline double correlation(const std::vector<float>& a, const std::vector<float>& b,
                          const std::vector<std::uint8_t>& mask) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!mask[i]) continue;
    sa += a[i];
    sb += b[i];
    saa += static_cast<double>(a[i]) * a[i];
    sbb += static_cast<double>(b[i]) * b[i];
    sab += static_cast<double>(a[i]) * b[i];
    ++n;
  }
  if (n < 2) return NAN;
  const double cov = sab / n - (sa / n) * (sb / n);
  const double va = saa / n - (sa / n) * (sa / n);
  const double vb = sbb / n - (sb / n) * (sb / n);
  return cov / std::sqrt(va * vb);
}

/// Largest and mean absolute difference of two equally long sequences.
struct Difference {
  double max = 0.0, mean = 0.0;
  double above = 0.0;  // fraction of values that differ by more than the threshold
};
inline Difference difference(const std::vector<float>& a, const std::vector<float>& b,
                             double threshold = 0.02) {
  Difference d;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double e = std::abs(static_cast<double>(a[i]) - b[i]);
    d.max = std::max(d.max, e);
    d.mean += e;
    if (e > threshold) d.above += 1.0;
  }
  if (!a.empty()) {
    d.mean /= static_cast<double>(a.size());
    d.above /= static_cast<double>(a.size());
  }
  return d;
}

/// A rotor's wall of cells whose splits are nearly tied: 400 pentagons
/// whose fifth point makes a nearly straight corner (its turn within 2% of
/// the sine core/mesh/polygon.h takes as straight, half of them bent out
/// and half in) and 400 quadrilaterals whose diagonal from the first point
/// is shorter by the 0.2% split_quad takes as a tie, give or take 1e-5; on
/// a cylinder of radius 0.4 about +Z, cells 1 cm across. Polygons as VTK's
/// cell arrays hold them.
struct Rotor {
  std::vector<glm::vec3> points;
  std::vector<long> offsets{0}, ids;
};

inline Rotor nearly_tied_rotor() {
  Rotor r;
  const auto add = [&](const std::vector<glm::dvec2>& corners) {  // (angle, height)
    for (const glm::dvec2& c : corners) {
      r.ids.push_back(static_cast<long>(r.points.size()));
      r.points.emplace_back(0.4 * std::cos(c.x), 0.4 * std::sin(c.x), c.y);
    }
    r.offsets.push_back(static_cast<long>(r.ids.size()));
  };
  constexpr double da = 0.025, dz = 0.01;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 10; ++j) {
      const double a = i * da, z = j * dz;
      const double sine = 1e-4 * (1.0 + 0.02 * (((i * 7 + j * 3) % 11) - 5) / 5.0);
      const double bend = ((i + j) % 2 ? 1.0 : -1.0) * sine * dz / 4.0;
      add({{a, z}, {a + da, z}, {a + da, z + dz}, {a + da / 2.0, z + dz + bend}, {a, z + dz}});
      const double shrink = 2e-3 * (1.0 + 5e-3 * (((i * 5 + j * 7) % 11) - 5) / 5.0);
      add({{a, z + 0.2},
           {a + da, z + 0.2},
           {a + da * (1.0 - shrink), z + 0.2 + dz},
           {a, z + 0.2 + dz}});
    }
  return r;
}

/// `points` turned by `degrees` about `axis` (unit) through the origin.
inline std::vector<glm::vec3> turned(const std::vector<glm::vec3>& points, double degrees,
                                     const glm::dvec3& axis) {
  const glm::dmat4 turn = glm::rotate(glm::dmat4(1.0), glm::radians(degrees), axis);
  std::vector<glm::vec3> out;
  out.reserve(points.size());
  for (const glm::vec3& p : points) out.emplace_back(turn * glm::dvec4(glm::dvec3(p), 1.0));
  return out;
}

/// Pixels of `image` within 30 of the colour (r, g, b) in each channel: a
/// colour the picture should (or should not) show, such as a topology
/// kind's.
inline std::size_t pixels_of_colour(const ImageU8& image, int r, int g, int b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i + 2 < image.pixels.size();
       i += static_cast<std::size_t>(image.channels))
    n += std::abs(image.pixels[i] - r) < 30 && std::abs(image.pixels[i + 1] - g) < 30 &&
         std::abs(image.pixels[i + 2] - b) < 30;
  return n;
}

}  // namespace ibfvs::test
