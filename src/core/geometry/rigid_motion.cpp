#include "ibfvs/core/geometry/rigid_motion.h"

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <glm/geometric.hpp>

#include "ibfvs/core/support/error.h"

namespace ibfvs {

namespace {

// (R(phi) - I) l for the rotation by phi about the unit axis a; 1 - cos as
// 2 sin^2(phi / 2), which keeps its digits for small angles.
glm::vec3 turned_less_still(const glm::vec3& l, const glm::vec3& a, float phi) {
  const float half = std::sin(0.5f * phi);
  const glm::vec3 across = glm::cross(a, l);
  return std::sin(phi) * across + 2.0f * half * half * glm::cross(a, across);
}

// The moments of one vertex's one-ring, relative to the vertex itself (in
// both steps), so that the covariance keeps its digits far from the origin.
struct Moments {
  double n = 0.0;
  Eigen::Vector3d sx = Eigen::Vector3d::Zero(), sy = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sxy = Eigen::Matrix3d::Zero();
  double sxx = 0.0, syy = 0.0;
  void add(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
    n += 1.0;
    sx += x;
    sy += y;
    sxy += x * y.transpose();
    sxx += x.squaredNorm();
    syy += y.squaredNorm();
  }
};

Eigen::Vector3d to_eigen(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

constexpr double kMinAngle = 1e-6;                              // radians: a translation
constexpr double kMaxAngle = 179.0 * std::numbers::pi / 180.0;  // the direction is lost
constexpr double kFlat = 1e-9;   // second singular value below this share of the first: a line
constexpr double kRigid = 1e-3;  // fit residual within this share of the one-ring's size

}  // namespace

glm::vec3 rotate_by(const glm::vec3& v, const glm::vec3& omega) {
  const float theta = glm::length(omega);
  if (!(theta > 0.0f)) return v;
  return v + turned_less_still(v, omega / theta, theta);
}

glm::vec3 interpolate_position(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& omega,
                               const glm::vec3& lever, float m) {
  const float theta = glm::length(omega);
  if (!(theta > 0.0f)) return p0 + m * (p1 - p0);
  const glm::vec3 a = omega / theta;
  const glm::vec3 rest = p1 - p0 - turned_less_still(lever, a, theta);
  return p0 + turned_less_still(lever, a, m * theta) + m * rest;
}

glm::vec3 interpolate_normal(const glm::vec3& n0, const glm::vec3& n1, const glm::vec3& omega,
                             float m) {
  const glm::vec3 n = rotate_by(n0, m * omega) * (1.0f - m) + rotate_by(n1, (m - 1.0f) * omega) * m;
  const float length = glm::length(n);
  return length > 0.0f ? n / length : n0;
}

SurfaceMotion fit_surface_motion(std::span<const Triangle> triangles,
                                 std::span<const glm::vec3> from, std::span<const glm::vec3> to) {
  if (from.size() != to.size())
    throw InputError("surface motion: the steps have " + std::to_string(from.size()) + " and " +
                     std::to_string(to.size()) + " points");
  const std::size_t n = from.size();
  std::vector<Moments> ring(n);
  for (const Triangle& t : triangles) {
    for (const std::uint32_t i : t)
      if (i >= n)
        throw InputError("surface motion: a triangle names point " + std::to_string(i) + " of " +
                         std::to_string(n));
    for (const std::uint32_t v : t) {
      const Eigen::Vector3d p0 = to_eigen(from[v]), p1 = to_eigen(to[v]);
      for (const std::uint32_t u : t) ring[v].add(to_eigen(from[u]) - p0, to_eigen(to[u]) - p1);
    }
  }
  SurfaceMotion motion;
  motion.omega.assign(n, glm::vec3(0.0f));
  motion.lever.assign(n, glm::vec3(0.0f));
  std::size_t rigid = 0;
#pragma omp parallel for schedule(static) reduction(+ : rigid)
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(n); ++k) {
    const auto i = static_cast<std::size_t>(k);
    const Moments& r = ring[i];
    if (r.n < 3.0) continue;
    const Eigen::Vector3d gx = r.sx / r.n, gy = r.sy / r.n;
    const Eigen::Matrix3d h = r.sxy - r.n * gx * gy.transpose();
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Vector3d s = svd.singularValues();
    if (!(s(0) > 0.0) || s(1) <= kFlat * s(0)) continue;  // a point or a line: the chord
    Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
    d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
    const Eigen::Matrix3d rot = svd.matrixV() * d * svd.matrixU().transpose();
    // How rigid: the spread left after the fit against the one-ring's own.
    const double spread_x = r.sxx - r.n * gx.squaredNorm();
    const double spread_y = r.syy - r.n * gy.squaredNorm();
    const double left = std::max(spread_x + spread_y - 2.0 * (rot * h).trace(), 0.0);
    if (left <= kRigid * kRigid * spread_x) ++rigid;
    const Eigen::AngleAxisd turn(rot);
    const double theta = turn.angle();
    if (theta < kMinAngle || theta > kMaxAngle) continue;
    const Eigen::Vector3d a = turn.axis().normalized();
    // The fit maps a point X of the first step to rot (X - p0 - gx) + p1 + gy:
    // rot X + t. The screw's axis passes through c, (I - rot) c = t's part
    // across the axis: c = (t + cot(theta / 2) a x t) / 2 (in the plane
    // through the origin across a).
    const Eigen::Vector3d p0 = to_eigen(from[i]), p1 = to_eigen(to[i]);
    const Eigen::Vector3d t = p1 + gy - rot * (p0 + gx);
    const Eigen::Vector3d across = t - t.dot(a) * a;
    const Eigen::Vector3d c = 0.5 * (across + a.cross(across) / std::tan(0.5 * theta));
    const Eigen::Vector3d lever = p0 - c;
    motion.omega[i] = glm::vec3(a.x() * theta, a.y() * theta, a.z() * theta);
    motion.lever[i] = glm::vec3(lever.x(), lever.y(), lever.z());
  }
  motion.rigid = rigid;
  return motion;
}

std::vector<glm::vec3> surface_at(std::span<const glm::vec3> from, std::span<const glm::vec3> to,
                                  const SurfaceMotion& motion, float m) {
  std::vector<glm::vec3> out(from.size());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = motion.empty()
                 ? from[i] + m * (to[i] - from[i])
                 : interpolate_position(from[i], to[i], motion.omega[i], motion.lever[i], m);
  return out;
}

}  // namespace ibfvs
