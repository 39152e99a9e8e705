#include "ibfvs/core/fields/linear2.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace ibfvs {

double Eigen2::largest_rate() const {
  return std::max(std::abs(value[0]), std::abs(value[1]));
}

Eigen2 eigen2(const Mat2& m) {
  Eigen2 e;
  const double trace = m.trace(), det = m.det();
  const double disc = trace * trace - 4.0 * det;
  if (disc < 0.0) {
    e.real = false;
    const double im = 0.5 * std::sqrt(-disc);
    e.value = {0.5 * trace, 0.5 * trace};
    e.imag = {-im, im};
    return e;
  }
  const double root = std::sqrt(disc);
  // The smaller root without cancellation: trace and root of one sign add.
  const double big = trace >= 0.0 ? 0.5 * (trace + root) : 0.5 * (trace - root);
  const double small = big != 0.0 ? det / big : 0.0;
  e.value = {std::min(big, small), std::max(big, small)};
  for (int k = 0; k < 2; ++k) {
    // (J - l I) x = 0: x = (b, l - a) or (l - d, c), whichever is longer.
    const double l = e.value[k];
    const double x1 = m.b, y1 = l - m.a, x2 = l - m.d, y2 = m.c;
    const bool first = x1 * x1 + y1 * y1 >= x2 * x2 + y2 * y2;
    double x = first ? x1 : x2, y = first ? y1 : y2;
    const double len = std::hypot(x, y);
    if (len > 0.0) {
      x /= len;
      y /= len;
    } else {  // a multiple of the identity: every vector; the axes
      x = k == 0 ? 1.0 : 0.0;
      y = k == 0 ? 0.0 : 1.0;
    }
    e.vector[k] = {x, y};
  }
  return e;
}

std::array<double, 2> TriangleFrame::of(const glm::dvec3& v) const {
  return {glm::dot(v, e1), glm::dot(v, e2)};
}

TriangleFrame triangle_frame(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2) {
  TriangleFrame f;
  f.origin = p0;
  const glm::dvec3 u = p1 - p0, v = p2 - p0;
  const glm::dvec3 n = glm::cross(u, v);
  const double area2 = glm::length(n);
  f.area = 0.5 * area2;
  f.valid = area2 > 1e-12 * glm::dot(u, u) + 1e-300 && std::isfinite(area2);
  if (!f.valid) return f;
  f.normal = n / area2;
  f.e1 = glm::normalize(u);
  f.e2 = glm::cross(f.normal, f.e1);
  return f;
}

Mat2 triangle_jacobian(const TriangleFrame& frame, const glm::dvec3& p1, const glm::dvec3& p2,
                       const glm::dvec3& w0, const glm::dvec3& w1, const glm::dvec3& w2) {
  const auto x1 = frame.of(p1 - frame.origin), x2 = frame.of(p2 - frame.origin);
  const auto m1 = frame.of(w1 - w0), m2 = frame.of(w2 - w0);
  const double xdet = x1[0] * x2[1] - x2[0] * x1[1];
  if (xdet == 0.0) return {};
  // X = [x1 x2] (columns), X^-1 = [x2y -x2x; -x1y x1x] / det.
  const double i00 = x2[1] / xdet, i01 = -x2[0] / xdet, i10 = -x1[1] / xdet, i11 = x1[0] / xdet;
  return {m1[0] * i00 + m2[0] * i10, m1[0] * i01 + m2[0] * i11, m1[1] * i00 + m2[1] * i10,
          m1[1] * i01 + m2[1] * i11};
}

}  // namespace ibfvs
