// The page's binary block: the surface, every step's vectors, its motion or
// its meshes of their own, the noise phases, the colour map and the optional
// arrays, each named in the header (web/schema/page.schema.json: Arrays).

#include <algorithm>
#include <cmath>
#include <cstring>

#include <meshoptimizer.h>
#include <glm/gtc/packing.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "ibfvs/core/geometry/rigid_motion.h"
#include "ibfvs/core/image/colormap.h"
#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/hash.h"
#include "page_json.h"

namespace ibfvs::page {

Json vec3(const glm::vec3& v) {
  return Json::array({v.x, v.y, v.z});
}

Json matrix(const glm::mat4& m) {
  const float* p = glm::value_ptr(m);
  return Json(std::vector<float>(p, p + 16));
}

Json Block::add_bytes(const void* data, std::size_t bytes, std::size_t length) {
  while (bytes_.size() % 4 != 0) bytes_.push_back(0);
  const std::size_t offset = bytes_.size();
  bytes_.resize(offset + bytes);
  if (bytes > 0) std::memcpy(bytes_.data() + offset, data, bytes);
  return {{"offset", offset}, {"length", length}};
}

Json Block::add_encoded_vertices(const void* data, std::size_t elements, std::size_t stride,
                                 std::size_t components) {
  const std::size_t count = elements / components;
  std::vector<unsigned char> encoded(meshopt_encodeVertexBufferBound(count, stride));
  encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data, count, stride));
  Json ref = add(encoded);
  ref["codec"] = "vertex";
  ref["stride"] = stride;
  ref["elements"] = elements;
  return ref;
}

Json Block::add_indices(const std::vector<std::uint32_t>& indices, std::size_t vertices) {
  std::vector<unsigned char> encoded(meshopt_encodeIndexBufferBound(indices.size(), vertices));
  encoded.resize(
      meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(), indices.size()));
  Json ref = add(encoded);
  ref["codec"] = "index";
  ref["elements"] = indices.size();
  return ref;
}

namespace {

std::int8_t snorm8(float v) {
  return static_cast<std::int8_t>(std::lround(std::clamp(v, -1.0f, 1.0f) * 127.0f));
}

// Positions in 16 bits within the box; normals in 8-bit snorm; vectors in
// half floats (they span decades: a fixed-point code would lose the slow).
// Four a vertex: the codec's stride is a multiple of 4 bytes.
struct Packer {
  glm::vec3 lo, extent;
  void vertex(const glm::vec3& r, const glm::vec3& n, std::vector<std::uint16_t>& q,
              std::vector<std::int8_t>& m) const {
    for (int c = 0; c < 3; ++c) {
      const float t = extent[c] > 0.0f ? (r[c] - lo[c]) / extent[c] : 0.0f;
      q.push_back(static_cast<std::uint16_t>(std::lround(std::clamp(t, 0.0f, 1.0f) * 65535.0f)));
      m.push_back(snorm8(n[c]));
    }
    q.push_back(0);
    m.push_back(0);
  }
  static void vectors(const std::vector<glm::vec3>& field, std::vector<std::uint16_t>& out) {
    for (const glm::vec3& v : field) {
      for (int c = 0; c < 3; ++c) out.push_back(glm::packHalf1x16(v[c]));
      out.push_back(0);
    }
  }
};

// The motion: the vertices whose stored point or normal differs from the
// first step's at some step, and for each step theirs, a step the same as
// the one before it stored once.
Json motion(const TriMesh& mesh, const std::vector<StepData>& data, const Packer& pack,
            const std::vector<std::uint16_t>& positions, const std::vector<std::int8_t>& normals,
            Block& block, WebPageReport* report) {
  const std::size_t steps = data.size();
  std::vector<std::vector<std::uint16_t>> step_q(steps);
  std::vector<std::vector<std::int8_t>> step_n(steps);
  std::vector<std::uint8_t> moves(mesh.vertex_count(), 0);
  for (std::size_t k = 0; k < steps; ++k) {
    const StepData& d = data[k];
    const std::vector<glm::vec3>& r = d.positions.empty() ? mesh.positions : d.positions;
    const std::vector<glm::vec3>& n = d.normals.empty() ? mesh.normals : d.normals;
    step_q[k].reserve(r.size() * 4);
    step_n[k].reserve(r.size() * 4);
    for (std::size_t i = 0; i < r.size(); ++i) pack.vertex(r[i], n[i], step_q[k], step_n[k]);
    for (std::size_t i = 0; i < r.size(); ++i)
      for (int c = 0; c < 3; ++c)
        moves[i] |= step_q[k][4 * i + c] != positions[4 * i + c] ||
                    step_n[k][4 * i + c] != normals[4 * i + c];
  }
  std::vector<std::uint32_t> movers;
  for (std::size_t i = 0; i < moves.size(); ++i)
    if (moves[i]) movers.push_back(static_cast<std::uint32_t>(i));
  std::vector<std::uint16_t> set_q, last_q;
  std::vector<std::int8_t> set_n, last_n;
  std::vector<int> set_of(steps, 0);
  int sets = 0;
  for (std::size_t k = 0; k < steps; ++k) {
    std::vector<std::uint16_t> q;
    std::vector<std::int8_t> m;
    q.reserve(movers.size() * 4);
    m.reserve(movers.size() * 4);
    for (const std::uint32_t i : movers) {
      q.insert(q.end(), step_q[k].begin() + 4 * i, step_q[k].begin() + 4 * i + 4);
      m.insert(m.end(), step_n[k].begin() + 4 * i, step_n[k].begin() + 4 * i + 4);
    }
    if (k > 0 && q == last_q && m == last_n) {
      set_of[k] = sets - 1;
      continue;
    }
    set_q.insert(set_q.end(), q.begin(), q.end());
    set_n.insert(set_n.end(), m.begin(), m.end());
    last_q = std::move(q);
    last_n = std::move(m);
    set_of[k] = sets++;
  }
  // Each step's screws towards the next (the last's towards the first, for
  // a page that loops), the moving vertices' as Session's StepPlayer fits
  // them (core/geometry/rigid_motion.h): omega and lever, float32 each; a
  // pair into or out of a mesh of its own, or that stands still, none.
  std::vector<float> screws;
  screws.reserve(steps * movers.size() * 6);
  for (std::size_t k = 0; k < steps; ++k) {
    const StepData &a = data[k], &b = data[(k + 1) % steps];
    const auto points = [&](const StepData& d) -> const std::vector<glm::vec3>& {
      return d.positions.empty() ? mesh.positions : d.positions;
    };
    SurfaceMotion fit;
    if (!a.mesh && !b.mesh && points(a) != points(b))
      fit = fit_surface_motion(mesh.triangles, points(a), points(b));
    for (const std::uint32_t i : movers) {
      const glm::vec3 w = fit.empty() ? glm::vec3(0.0f) : fit.omega[i];
      const glm::vec3 l = fit.empty() ? glm::vec3(0.0f) : fit.lever[i];
      screws.insert(screws.end(), {w.x, w.y, w.z, l.x, l.y, l.z});
    }
  }
  const std::size_t before = block.bytes().size();
  Json out = {{"moving", block.add(movers)},
              {"positions", block.add_vertices(set_q, 4)},
              {"normals", block.add_vertices(set_n, 4)},
              {"sets", set_of}};
  const std::size_t points = block.bytes().size();
  out["screws"] = block.add_vertices(screws, 6);
  if (report) {
    report->moving_vertices = movers.size();
    report->motion_sets = static_cast<std::size_t>(sets);
    report->motion = points - before;
    report->screws = block.bytes().size() - points;
  }
  return out;
}

// (colour, beta) per vertex: every step's where they change from step to
// step (a transient result coloured by its own magnitude), as the session
// sets them at each step; else the first step's.
Json scalars(const PreparedScene& p, const std::vector<StepData>& data, Block& block) {
  const std::size_t vertices = p.mesh->vertex_count();
  const auto put = [&](const std::vector<float>& colour, const std::vector<float>& beta,
                       std::vector<float>& out) {
    for (std::size_t i = 0; i < vertices; ++i) {
      out.push_back(colour.empty() ? 0.0f : colour[i]);
      out.push_back(beta.empty() ? 0.0f : beta[i]);
    }
  };
  std::vector<float> values;
  put(p.color_scalar, p.beta_scalar, values);
  const std::size_t first = values.size();
  bool changing = false;
  for (std::size_t k = 1; k < data.size() && p.step_data; ++k) {
    const StepData& d = data[k];  // a step on a mesh of its own: its scalars go with it
    put(d.mesh ? std::vector<float>() : d.color_scalar,
        d.mesh ? std::vector<float>() : d.beta_scalar, values);
    changing = changing || !std::equal(values.begin(), values.begin() + first,
                                       values.end() - static_cast<std::ptrdiff_t>(first));
  }
  if (!changing) values.resize(first);
  Json ref = block.add_vertices(values, 2);
  ref["steps"] = values.size() / first;
  return ref;
}

// A step whose triangles are its own (a changing mesh): its points and
// normals (in the same box), triangles, vectors and scalars.
Json step_mesh(const StepData& d, const Packer& pack, bool scalars, Block& block) {
  const TriMesh& m = *d.mesh;
  std::vector<std::uint16_t> q, v;
  std::vector<std::int8_t> n;
  for (std::size_t i = 0; i < m.vertex_count(); ++i)
    pack.vertex(m.positions[i], m.normals[i], q, n);
  Packer::vectors(d.field, v);
  std::vector<std::uint32_t> ids;
  for (const Triangle& t : m.triangles) ids.insert(ids.end(), t.begin(), t.end());
  Json out = {{"vertex_count", m.vertex_count()},
              {"index_count", ids.size()},
              {"cull", closed_orientation(m)},
              {"positions", block.add_vertices(q, 4)},
              {"normals", block.add_vertices(n, 4)},
              {"vectors", block.add_vertices(v, 4)},
              {"indices", block.add_indices(ids, m.vertex_count())}};
  if (scalars) {
    std::vector<float> sc;
    for (std::size_t i = 0; i < m.vertex_count(); ++i) {
      sc.push_back(d.color_scalar.empty() ? 0.0f : d.color_scalar[i]);
      sc.push_back(d.beta_scalar.empty() ? 0.0f : d.beta_scalar[i]);
    }
    out["scalars"] = block.add_vertices(sc, 2);
  }
  return out;
}

// F_t's first colours, one per noise cell (IbfvsRenderer::
// fill_texture_with_cell_colors): half floats, as F_t holds them.
Json cells(const PreparedScene& p, Block& block) {
  const float scale = p.settings.noise.scale;
  const int columns = static_cast<int>(std::ceil(static_cast<float>(p.width) / scale)) + 1;
  const int rows = static_cast<int>(std::ceil(static_cast<float>(p.height) / scale)) + 1;
  std::vector<std::uint16_t> values;
  values.reserve(static_cast<std::size_t>(columns) * rows * 4);
  for (std::uint64_t cell = 0; cell < static_cast<std::uint64_t>(columns) * rows; ++cell) {
    for (std::uint64_t c = 0; c < 3; ++c)
      values.push_back(glm::packHalf1x16(hash_uniform(p.scene.seed, 3 * cell + c)));
    values.push_back(0);
  }
  Json ref = block.add(values);
  ref["columns"] = columns;
  ref["scale"] = scale;
  return ref;
}

}  // namespace

Json arrays(const PreparedScene& p, const SceneSteps& steps, const std::vector<float>& phi,
            Block& block, WebPageReport* report) {
  const TriMesh& mesh = *p.mesh;
  const RenderSettings& s = p.settings;
  const Packer pack{steps.lo, steps.hi - steps.lo};
  std::vector<std::uint16_t> positions;
  std::vector<std::int8_t> normals;
  positions.reserve(mesh.positions.size() * 4);
  normals.reserve(mesh.positions.size() * 4);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    pack.vertex(mesh.positions[i], mesh.normals[i], positions, normals);
  // Every time step of an unsteady field, one after the other (a step on a
  // mesh of its own: zeros here, its vectors with its mesh).
  std::vector<std::uint16_t> vectors;
  vectors.reserve(steps.data.size() * mesh.positions.size() * 4);
  for (const StepData& d : steps.data) {
    if (d.mesh)
      vectors.resize(vectors.size() + mesh.positions.size() * 4, 0);
    else
      Packer::vectors(d.field, vectors);
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(mesh.triangles.size() * 3);
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) indices.push_back(static_cast<std::uint32_t>(t[c]));
  std::vector<std::uint16_t> phases;
  phases.reserve(phi.size());
  for (const float v : phi)
    phases.push_back(static_cast<std::uint16_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 65535.0f)));
  std::vector<std::uint8_t> colours;
  for (int i = 0; i < 256; ++i) {
    const glm::vec3 c = s.color_table.size() == 256
                            ? s.color_table[static_cast<std::size_t>(i)]
                            : color_map(s.color_map, static_cast<float>(i) / 255.0f);
    for (int k = 0; k < 3; ++k)
      colours.push_back(
          static_cast<std::uint8_t>(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f)));
    colours.push_back(255);
  }

  // (The order in the block is free: the header names every array's offset.)
  Json moved;
  if (steps.moving) moved = motion(mesh, steps.data, pack, positions, normals, block, report);
  Json out;
  out["positions"] = block.add_vertices(positions, 4);
  out["positions"]["min"] = vec3(steps.lo);
  out["positions"]["max"] = vec3(steps.hi);
  out["normals"] = block.add_vertices(normals, 4);
  out["vectors"] = block.add_vertices(vectors, 4);
  out["indices"] = block.add_indices(indices, mesh.positions.size());
  out["phases"] = block.add(phases);
  out["color_map"] = block.add(colours);
  if (s.use_color || s.use_beta) out["scalars"] = scalars(p, steps.data, block);
  std::size_t other_meshes = 0;
  for (const StepData& d : steps.data) {
    if (!d.mesh) continue;
    out["meshes"].push_back(step_mesh(d, pack, s.use_color || s.use_beta, block));
    ++other_meshes;
  }
  if (report && other_meshes > 0) report->other_meshes = other_meshes;
  if (const ImageU8& image = p.surface_image; !image.pixels.empty()) {
    // The surface colour (RGBA8, bottom row first as the GL texture takes
    // it), through the vertex codec: 4 bytes a pixel, deltas along the row.
    if (image.channels != 4)
      throw InputError("page of " + p.mesh_name + ": the surface image must be RGBA");
    Json ref = block.add_vertices(image.pixels, 4);
    ref["width"] = image.width;
    ref["height"] = image.height;
    out["surface_image"] = std::move(ref);
  }
  if (p.scene.init == InitMode::RandomCells) out["cells"] = cells(p, block);
  if (steps.moving) out["motion"] = std::move(moved);
  return out;
}

}  // namespace ibfvs::page
