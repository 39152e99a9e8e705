#include "ibfvs/core/mesh/mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "ibfvs/core/support/error.h"

namespace ibfvs {

float Bounds::diagonal() const {
  return glm::length(max - min);
}

Bounds mesh_bounds(const TriMesh& mesh) {
  if (mesh.triangles.empty()) throw InputError("mesh has no triangles");
  Bounds b;
  b.min = glm::vec3(std::numeric_limits<float>::max());
  b.max = glm::vec3(std::numeric_limits<float>::lowest());
  for (const Triangle& t : mesh.triangles) {
    for (std::uint32_t i : t) {
      b.min = glm::min(b.min, mesh.positions[i]);
      b.max = glm::max(b.max, mesh.positions[i]);
    }
  }
  const glm::vec3 c = b.centre();
  float r2 = 0.0f;
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t i : t) {
      const glm::vec3 d = mesh.positions[i] - c;
      r2 = std::max(r2, glm::dot(d, d));
    }
  b.radius = std::sqrt(r2);
  return b;
}

namespace {
// acos to 7e-5 radians (Abramowitz and Stegun 4.4.45), for the corner
// weights: a moving surface's normals are computed at every step change,
// and acosf was most of that.
float corner_angle(float c) {
  const float x = std::abs(c);
  const float r =
      std::sqrt(1.0f - x) * (1.5707288f + x * (-0.2121144f + x * (0.0742610f - x * 0.0187293f)));
  return c >= 0.0f ? r : 3.14159265f - r;
}
}  // namespace

namespace {

// `into`'s array followed by `more`'s, where both have one per vertex (or
// `into` had no vertices); else none.
template <class T>
void append_array(std::vector<T>& into, const std::vector<T>& more, std::size_t into_vertices,
                  std::size_t more_vertices) {
  const bool mine = into.size() == into_vertices && (into_vertices > 0 || !more.empty());
  if (mine && more.size() == more_vertices)
    into.insert(into.end(), more.begin(), more.end());
  else
    into.clear();
}

template <class T>
void append_named(std::map<std::string, std::vector<T>>& into,
                  const std::map<std::string, std::vector<T>>& more, std::size_t into_vertices,
                  std::size_t more_vertices) {
  if (into_vertices == 0) {
    into = more;
    return;
  }
  for (auto it = into.begin(); it != into.end();) {
    const auto other = more.find(it->first);
    if (other == more.end()) {
      it = into.erase(it);
      continue;
    }
    append_array(it->second, other->second, into_vertices, more_vertices);
    it = it->second.size() == into_vertices + more_vertices ? std::next(it) : into.erase(it);
  }
}

}  // namespace

void append_mesh(TriMesh& into, const TriMesh& more) {
  const std::size_t n = into.vertex_count(), m = more.vertex_count();
  append_array(into.normals, more.normals, n, m);
  append_array(into.vectors, more.vectors, n, m);
  append_named(into.scalars, more.scalars, n, m);
  append_named(into.vector_arrays, more.vector_arrays, n, m);
  if (n == 0) into.other_arrays = more.other_arrays;
  into.positions.insert(into.positions.end(), more.positions.begin(), more.positions.end());
  const auto offset = static_cast<std::uint32_t>(n);
  into.triangles.reserve(into.triangles.size() + more.triangles.size());
  for (const Triangle& t : more.triangles)
    into.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

void compute_vertex_normals(TriMesh& mesh) {
  std::vector<glm::vec3> acc(mesh.positions.size(), glm::vec3(0.0f));
  for (const Triangle& t : mesh.triangles) {
    const glm::vec3 p[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
    const glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
    const float len = glm::length(n);
    if (!(len > 0.0f) || !std::isfinite(len)) continue;
    const glm::vec3 unit = n / len;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 a = p[(k + 1) % 3] - p[k];
      const glm::vec3 b = p[(k + 2) % 3] - p[k];
      const float la2 = glm::dot(a, a), lb2 = glm::dot(b, b);
      if (!(la2 > 0.0f && lb2 > 0.0f)) continue;
      const float c = std::clamp(glm::dot(a, b) / std::sqrt(la2 * lb2), -1.0f, 1.0f);
      acc[t[k]] += corner_angle(c) * unit;
    }
  }
  mesh.normals.resize(acc.size());
  for (std::size_t i = 0; i < acc.size(); ++i) {
    const float len = glm::length(acc[i]);
    mesh.normals[i] = (len > 0.0f && std::isfinite(len)) ? acc[i] / len : glm::vec3(0, 0, 1);
  }
}

void validate_mesh(const TriMesh& mesh, const std::string& source) {
  const std::size_t n = mesh.positions.size();
  if (mesh.triangles.empty()) throw InputError(source + ": the mesh has no triangles");
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(source + ": vertex " + std::to_string(i) +
                       " has a non-finite coordinate (NaN or infinity)");
  }
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (std::uint32_t i : mesh.triangles[f])
      if (i >= n)
        throw InputError(source + ": triangle " + std::to_string(f) + " references vertex " +
                         std::to_string(i) + " but there are only " + std::to_string(n));
  if (!mesh.normals.empty() && mesh.normals.size() != n)
    throw InputError(source + ": normal count differs from vertex count");
  if (!mesh.vectors.empty() && mesh.vectors.size() != n)
    throw InputError(source + ": vector count differs from vertex count");
  for (const auto& [name, values] : mesh.scalars)
    if (values.size() != n)
      throw InputError(source + ": property '" + name + "' count differs from vertex count");
  for (const auto& [name, values] : mesh.vector_arrays)
    if (values.size() != n)
      throw InputError(source + ": array '" + name + "' count differs from vertex count");
}

namespace {

template <class T>
std::vector<T> area_weighted(const TriMesh& mesh, const std::vector<T>& values) {
  if (values.size() != mesh.triangles.size())
    throw InputError("per-triangle data has " + std::to_string(values.size()) + " values for " +
                     std::to_string(mesh.triangles.size()) + " triangles");
  const std::size_t n = mesh.vertex_count();
  std::vector<T> sum(n, T(0.0f)), plain(n, T(0.0f));
  std::vector<float> weight(n, 0.0f);
  std::vector<std::uint32_t> count(n, 0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (t[0] >= n || t[1] >= n || t[2] >= n) continue;
    const glm::vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    const float area = 0.5f * glm::length(glm::cross(b - a, c - a));
    for (const std::uint32_t v : t) {
      if (std::isfinite(area) && area > 0.0f) {
        sum[v] += area * values[f];
        weight[v] += area;
      }
      plain[v] += values[f];
      ++count[v];
    }
  }
  for (std::size_t v = 0; v < n; ++v)
    sum[v] = weight[v] > 0.0f ? sum[v] / weight[v]
             : count[v] > 0   ? plain[v] / static_cast<float>(count[v])
                              : T(0.0f);
  return sum;
}

}  // namespace

std::vector<float> triangle_to_vertex(const TriMesh& mesh, const std::vector<float>& values) {
  return area_weighted(mesh, values);
}

std::vector<glm::vec3> triangle_to_vertex(const TriMesh& mesh,
                                          const std::vector<glm::vec3>& values) {
  return area_weighted(mesh, values);
}

Topology analyze_topology(const TriMesh& mesh) {
  Topology top;
  std::vector<std::uint64_t> keys;  // one per triangle side: (min, max) vertex index
  keys.reserve(mesh.triangles.size() * 3);
  std::vector<bool> used(mesh.vertex_count(), false);
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t a = t[k], b = t[(k + 1) % 3];
      keys.push_back(std::min(a, b) << 32 | std::max(a, b));
      used[t[k]] = true;
    }
  std::sort(keys.begin(), keys.end());
  // Union-find over the vertices of boundary edges: each set is one loop.
  std::vector<std::uint32_t> parent(mesh.vertex_count());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<std::uint32_t>(i);
  const auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<std::uint32_t> on_boundary;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    ++top.edges;
    if (j - i == 1) {
      ++top.boundary_edges;
      const auto a = static_cast<std::uint32_t>(keys[i] >> 32);
      const auto b = static_cast<std::uint32_t>(keys[i] & 0xffffffffu);
      parent[find(a)] = find(b);
      on_boundary.push_back(a);
      on_boundary.push_back(b);
    } else if (j - i > 2) {
      ++top.nonmanifold_edges;
    }
    i = j;
  }
  std::sort(on_boundary.begin(), on_boundary.end());
  on_boundary.erase(std::unique(on_boundary.begin(), on_boundary.end()), on_boundary.end());
  for (const std::uint32_t v : on_boundary) top.boundary_loops += find(v) == v;
  top.isolated_vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), false));
  return top;
}

bool most_edges_shared(std::span<const Triangle> a, std::span<const Triangle> b) {
  // Each mesh's edges, once each: a polygon split otherwise keeps its own
  // edges and changes only those inside it.
  const auto edges = [](std::span<const Triangle> triangles) {
    std::vector<std::uint64_t> e;
    e.reserve(3 * triangles.size());
    for (const Triangle& t : triangles)
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t i = t[static_cast<std::size_t>(k)], j = t[(k + 1) % 3];
        e.push_back(std::min(i, j) << 32 | std::max(i, j));
      }
    std::sort(e.begin(), e.end());
    e.erase(std::unique(e.begin(), e.end()), e.end());
    return e;
  };
  const std::vector<std::uint64_t> known = edges(a), given = edges(b);
  std::size_t shared = 0;
  for (const std::uint64_t e : given)
    shared += std::binary_search(known.begin(), known.end(), e) ? 1 : 0;
  return !given.empty() && 2 * shared >= given.size();
}

bool points_correspond(const TriMesh& a, const TriMesh& b) {
  if (a.vertex_count() != b.vertex_count()) return false;
  return a.triangles == b.triangles || most_edges_shared(a.triangles, b.triangles);
}

std::uint64_t topology_hash(const TriMesh& mesh) {
  // splitmix64's finaliser on each word, folded in order: every index and
  // its position count (not a checksum that swapped triangles would keep).
  // Four lanes, triangle k in lane k mod 4, so that the multiplications of
  // consecutive triangles overlap: a step change of a host's data hashes
  // its triangles once.
  const auto mix = [](std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  };
  constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ull;
  std::array<std::uint64_t, 4> lanes{};
  for (std::size_t l = 0; l < lanes.size(); ++l)
    lanes[l] = mix(mesh.vertex_count() + kGolden * (l + 1));
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const Triangle& t = mesh.triangles[k];
    std::uint64_t& h = lanes[k & 3];
    h = mix(h ^ (((std::uint64_t{t[0]} << 32) | t[1]) + kGolden)) + (h << 6);
    h = mix(h ^ (std::uint64_t{t[2]} + kGolden)) + (h << 6);
  }
  std::uint64_t h = mix(mesh.triangles.size() + kGolden);
  for (const std::uint64_t lane : lanes) h = mix(h ^ lane) + (h << 6);
  return h;
}

std::size_t remove_degenerate_triangles(TriMesh& mesh, bool by_area) {
  const std::size_t before = mesh.triangles.size();
  std::erase_if(mesh.triangles, [&](const Triangle& t) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
    if (!by_area) return false;
    const glm::vec3 n = glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                   mesh.positions[t[2]] - mesh.positions[t[0]]);
    return !(glm::dot(n, n) > 0.0f);
  });
  return before - mesh.triangles.size();
}

int closed_orientation(const TriMesh& mesh) {
  if (mesh.triangles.empty()) return 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) edges.emplace_back(t[k], t[(k + 1) % 3]);
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return 0;  // a->b twice
  for (const auto& [a, b] : edges)
    if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(b, a))) return 0;
  double volume = 0.0;  // six times the signed volume
  for (const Triangle& t : mesh.triangles) {
    const glm::dvec3 p(mesh.positions[t[0]]), q(mesh.positions[t[1]]), r(mesh.positions[t[2]]);
    volume += glm::dot(p, glm::cross(q, r));
  }
  return volume > 0.0 ? 1 : volume < 0.0 ? -1 : 0;
}

}  // namespace ibfvs
