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

}  // namespace ibfvs::test
