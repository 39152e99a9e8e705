#include "ibfvs/core/mesh/procedural.h"

#include <cmath>
#include <numbers>

#include <algorithm>
#include <string>

#include <glm/geometric.hpp>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/hash.h"

namespace ibfvs {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Triangulates a (cols+1) x (rows+1) vertex grid; `wrap_u` joins the last
// column to the first.
void grid_triangles(TriMesh& m, int cols, int rows, bool wrap_u, bool wrap_v) {
  const int vc = wrap_u ? cols : cols + 1;
  const auto id = [&](int i, int j) {
    const int rr = wrap_v ? rows : rows + 1;
    return static_cast<std::uint32_t>((j % rr) * vc + (i % vc));
  };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

}  // namespace

TriMesh make_torus(float R, float r, int segments, int sides) {
  TriMesh m;
  for (int j = 0; j < sides; ++j)
    for (int i = 0; i < segments; ++i) {
      const float u = 2 * kPi * static_cast<float>(i) / static_cast<float>(segments);
      const float v = 2 * kPi * static_cast<float>(j) / static_cast<float>(sides);
      const glm::vec3 dir(std::cos(u), 0, -std::sin(u));
      const glm::vec3 n = std::cos(v) * dir + glm::vec3(0, std::sin(v), 0);
      m.positions.push_back(R * dir + r * n);
      m.normals.push_back(n);
    }
  grid_triangles(m, segments, sides, true, true);
  return m;
}

TriMesh make_sphere(float radius, int stacks, int slices, float bump) {
  TriMesh m;
  for (int j = 0; j <= stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const float theta = kPi * static_cast<float>(j) / static_cast<float>(stacks);
      const float phi = 2 * kPi * static_cast<float>(i) / static_cast<float>(slices);
      const glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta),
                        std::sin(theta) * std::cos(phi));
      const float relief = 1.0f + bump * std::sin(5 * theta) * std::sin(4 * phi) * std::sin(theta);
      m.positions.push_back(radius * relief * n);
      m.normals.push_back(n);
    }
  // Rows 0 and `stacks` collapse to the poles; the triangles touching them are
  // kept with distinct indices but zero area at the pole, which is harmless.
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const auto id = [&](int ii, int jj) {
        return static_cast<std::uint32_t>(jj * slices + (ii % slices));
      };
      if (j > 0) m.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j)});
      if (j < stacks - 1) m.triangles.push_back({id(i + 1, j), id(i, j + 1), id(i + 1, j + 1)});
    }
  if (bump != 0.0f) compute_vertex_normals(m);
  return m;
}

TriMesh make_square(float half, int n) {
  TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      m.positions.emplace_back(-half + 2 * half * static_cast<float>(i) / static_cast<float>(n),
                               -half + 2 * half * static_cast<float>(j) / static_cast<float>(n),
                               0.0f);
      m.normals.emplace_back(0, 0, 1);
    }
  grid_triangles(m, n, n, false, false);
  return m;
}

TriMesh make_cylinder(float r, float h, int segments, int rings) {
  TriMesh m;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const float u = 2 * kPi * static_cast<float>(i) / static_cast<float>(segments);
      const glm::vec3 n(std::sin(u), 0, std::cos(u));
      m.positions.push_back(r * n + glm::vec3(0, -0.5f * h + h * static_cast<float>(j) / rings, 0));
      m.normals.push_back(n);
    }
  grid_triangles(m, segments, rings, true, false);
  return m;
}

TriMesh make_bspline_height_field(const std::vector<float>& controls, int columns, int rows,
                                  int resolution) {
  if (columns < 4 || rows < 4)
    throw InputError("height field: the control grid must be at least 4 x 4");
  if (controls.size() != static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows))
    throw InputError("height field: " + std::to_string(controls.size()) +
                     " control heights for a " + std::to_string(columns) + " x " +
                     std::to_string(rows) + " grid");
  if (resolution < 1 || resolution > 4096)
    throw InputError("height field: the resolution must be between 1 and 4096 cells");
  // Uniform cubic B-spline basis on one span, t in [0, 1].
  const auto basis = [](float t, float b[4]) {
    const float s = 1.0f - t;
    b[0] = s * s * s / 6.0f;
    b[1] = (3 * t * t * t - 6 * t * t + 4) / 6.0f;
    b[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6.0f;
    b[3] = t * t * t / 6.0f;
  };
  // Parameter u in [0, columns - 3] covers x in [-1, 1].
  const auto span = [](float u, int spans, int& i, float& t) {
    i = std::min(static_cast<int>(std::floor(u)), spans - 1);
    t = u - static_cast<float>(i);
  };
  TriMesh m;
  std::vector<float>& height = m.scalars["height"];
  for (int j = 0; j <= resolution; ++j)
    for (int i = 0; i <= resolution; ++i) {
      const float fx = static_cast<float>(i) / resolution, fy = static_cast<float>(j) / resolution;
      int si = 0, sj = 0;
      float tx = 0, ty = 0, bx[4], by[4];
      span(fx * static_cast<float>(columns - 3), columns - 3, si, tx);
      span(fy * static_cast<float>(rows - 3), rows - 3, sj, ty);
      basis(tx, bx);
      basis(ty, by);
      float z = 0.0f;
      for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a)
          z += bx[a] * by[b] *
               controls[static_cast<std::size_t>(sj + b) * static_cast<std::size_t>(columns) +
                        static_cast<std::size_t>(si + a)];
      // Height along +Y, the camera's up: the grid's x runs along +X and its
      // y along -Z (a rotation, so the triangles still face up).
      m.positions.emplace_back(2 * fx - 1, z, 1 - 2 * fy);
      height.push_back(z);
    }
  grid_triangles(m, resolution, resolution, false, false);
  compute_vertex_normals(m);
  return m;
}

std::vector<float> random_controls(int columns, int rows, float amplitude, std::uint32_t seed) {
  std::vector<float> p(static_cast<std::size_t>(std::max(columns, 0)) *
                       static_cast<std::size_t>(std::max(rows, 0)));
  for (std::size_t k = 0; k < p.size(); ++k) p[k] = amplitude * (2 * hash_uniform(seed, k) - 1);
  return p;
}

TriMesh make_icosahedron(float radius) {
  TriMesh m;
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  const glm::vec3 v[12] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                           {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                           {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (const glm::vec3& p : v) {
    m.positions.push_back(radius * glm::normalize(p));
    m.normals.push_back(glm::normalize(p));
  }
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  return m;
}

TriMesh make_height_field(float (*f)(float, float), float half, int n) {
  TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = -half + 2 * half * static_cast<float>(i) / static_cast<float>(n);
      const float y = -half + 2 * half * static_cast<float>(j) / static_cast<float>(n);
      m.positions.emplace_back(x, y, f(x, y));
    }
  grid_triangles(m, n, n, false, false);
  compute_vertex_normals(m);
  return m;
}

}  // namespace ibfvs
