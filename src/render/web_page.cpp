#include "ibfvs/render/web_page.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include <meshoptimizer.h>
#include <glm/gtc/packing.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "ibfvs/core/image/colormap.h"
#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/names.h"
#include "ibfvs/core/texture/display.h"
#include "ibfvs/core/texture/noise.h"
#include "ibfvs/render/ibfvs_renderer.h"
#include "ibfvs/render/pass_settings.h"

namespace ibfvs {

// The bundled runtime, generated at build time (web_runtime.cpp), or null.
extern const char* const kWebRuntime;

namespace {

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '<':
        out += "\\u003c";
        break;  // no "</script>" inside the page's script element
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

template <typename Range>
std::string json_numbers(const Range& values) {
  std::string out = "[";
  for (const auto v : values) {
    if (out.size() > 1) out += ",";
    out += json_number(static_cast<double>(v));
  }
  return out + "]";
}

std::string json_uniforms(const std::vector<shaders::UniformValue>& uniforms) {
  std::string out = "[";
  for (const auto& u : uniforms) {
    if (out.size() > 1) out += ",";
    const char* type = u.type == shaders::UniformValue::Type::Float ? "float"
                       : u.type == shaders::UniformValue::Type::Int ? "int"
                                                                    : "uint";
    out += "{\"name\":" + json_string(u.name) + ",\"type\":\"" + type +
           "\",\"values\":" + json_numbers(u.values) + (u.array ? ",\"array\":true}" : "}");
  }
  return out + "]";
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* const table =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4 + bytes.size() / 57 + 1);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t a = bytes[i], b = i + 1 < bytes.size() ? bytes[i + 1] : 0,
                        c = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const std::uint32_t n = (a << 16) | (b << 8) | c;
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
    if ((i / 3 + 1) % 19 == 0) out += '\n';  // lines of 76 characters
  }
  return out;
}

// The binary block: arrays appended at 4-byte boundaries, each named in the
// header with its offset and length in elements.
class Block {
 public:
  template <typename T>
  std::string add(const std::vector<T>& values, const std::string& extra = "") {
    while (bytes_.size() % 4 != 0) bytes_.push_back(0);
    const std::size_t offset = bytes_.size();
    bytes_.resize(offset + values.size() * sizeof(T));
    if (!values.empty())
      std::memcpy(bytes_.data() + offset, values.data(), values.size() * sizeof(T));
    return "{\"offset\":" + std::to_string(offset) +
           ",\"length\":" + std::to_string(values.size()) + extra + "}";
  }
  // Per-vertex arrays (components values a vertex, 4..256 bytes in all) and
  // triangle indices through meshoptimizer's codecs, which the page's
  // runtime decodes with the same library's decoder (npm meshoptimizer).
  template <typename T>
  std::string add_vertices(const std::vector<T>& values, std::size_t components,
                           const std::string& extra = "") {
    const std::size_t stride = components * sizeof(T), count = values.size() / components;
    std::vector<unsigned char> encoded(meshopt_encodeVertexBufferBound(count, stride));
    encoded.resize(
        meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), values.data(), count, stride));
    return add(encoded, ",\"codec\":\"vertex\",\"stride\":" + std::to_string(stride) +
                            ",\"elements\":" + std::to_string(values.size()) + extra);
  }
  std::string add_indices(const std::vector<std::uint32_t>& indices, std::size_t vertices) {
    std::vector<unsigned char> encoded(meshopt_encodeIndexBufferBound(indices.size(), vertices));
    encoded.resize(
        meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(), indices.size()));
    return add(encoded, ",\"codec\":\"index\",\"elements\":" + std::to_string(indices.size()));
  }
  [[nodiscard]] const std::vector<std::uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

std::int8_t snorm8(float v) {
  return static_cast<std::int8_t>(std::lround(std::clamp(v, -1.0f, 1.0f) * 127.0f));
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

using T = shaders::UniformValue::Type;

// One look of the page: what the pass is compiled with and set to for one
// style over the same data. `finest`: the columns and rows of the page's
// noise phases (a coarser grid takes the first of them).
std::string look_json(const PreparedScene& q, const std::string& name, std::string_view description,
                      glm::ivec2 finest, glm::vec3 centre, bool moving) {
  const RenderSettings& s = q.settings;
  // Random-cell colours make F_t a colour texture, as in the renderer.
  const bool colour_texture =
      shaders::colour_background(s) || q.scene.init == InitMode::RandomCells;
  shaders::ShaderFeatures f =
      shaders::features_for(s, colour_texture, !q.surface_image.pixels.empty(), false);
  f.moving = moving;
  const NoiseGrid grid(q.width, q.height, s.noise);
  const glm::ivec2 phase_size = glm::min(glm::ivec2(grid.columns(), grid.rows()), finest);
  const std::vector<shaders::UniformValue> grid_uniforms = {
      {"u_profile", T::Int, {static_cast<double>(static_cast<int>(s.noise.profile))}},
      {"u_spike_width", T::Float, {s.noise.spike_width}},
      {"u_seed", T::Uint, {static_cast<double>(s.noise.seed)}}};
  return "{\"name\":" + json_string(name) + ",\"description\":" + json_string(description) +
         ",\"background\":" +
         json_numbers(std::vector<float>{s.background.r, s.background.g, s.background.b}) +
         ",\"dt\":" + json_number(q.dt) + ",\"noise_rate\":" + json_number(s.noise.rate) +
         ",\"colour_texture\":" + (colour_texture ? "true" : "false") +
         ",\"texture_channels\":" + std::to_string(shaders::texture_channels(f)) +
         ",\"tap_texture\":" + (shaders::tap_texture(f) ? "true" : "false") +
         ",\"advect_previous\":" + (s.advect_view == AdvectView::Previous ? "true" : "false") +
         ",\"phase_size\":[" + std::to_string(phase_size.x) + "," + std::to_string(phase_size.y) +
         "],\"shaders\":{\"vertex\":" +
         json_string(shaders::ibfvs_vertex_source(f, shaders::Dialect::Es300)) + ",\"fragment\":" +
         json_string(shaders::ibfvs_fragment_source(f, shaders::Dialect::Es300)) +
         ",\"stats_fragment\":" +
         json_string(shaders::stats_fragment_source(!colour_texture, shaders::Dialect::Es300)) +
         ",\"display_fragment\":" +
         json_string(shaders::tap_texture(f)
                         ? shaders::display_fragment_source(f, shaders::Dialect::Es300)
                         : std::string()) +
         "},\"uniforms\":" + json_uniforms(shaders::settings_uniforms(s, f, phase_size, centre)) +
         ",\"grid_uniforms\":" + json_uniforms(grid_uniforms) + "}";
}

// A style that takes the page's data, with the scene in its look.
struct Restyle {
  EnumName<Style> style;
  PreparedScene scene;
};

// Every style that takes the scene's data (restyled), in table order: made
// once, for the noise grid and the looks.
std::vector<Restyle> restyles(const PreparedScene& p) {
  std::vector<Restyle> out;
  for (const auto& e : enum_entries<Style>()) {
    try {
      if (std::optional<PreparedScene> q = restyled(p, e.value)) out.push_back({e, std::move(*q)});
    } catch (const SettingError&) {
      // a setting of the scene that this style's defaults make invalid: left out
    }
  }
  return out;
}

// The page's looks: the scene's own first, then each style that takes the
// same data, each once.
std::string looks_json(const PreparedScene& p, const std::vector<Restyle>& styles,
                       glm::ivec2 finest, glm::vec3 centre, bool moving) {
  const auto body = [](const std::string& look) {
    return look.substr(look.find(",\"background\""));
  };
  std::vector<std::string> looks;
  // Named by its style when it is that style's look, else "as rendered".
  const auto pure = std::find_if(styles.begin(), styles.end(), [&](const Restyle& r) {
    return p.scene.style && r.style.value == *p.scene.style;
  });
  const std::string own =
      look_json(p, "as rendered", "the settings the page was written with", finest, centre, moving);
  const bool as_style = pure != styles.end() &&
                        body(look_json(pure->scene, "", "", finest, centre, moving)) == body(own);
  looks.push_back(as_style ? look_json(p, std::string(pure->style.name), pure->style.description,
                                       finest, centre, moving)
                           : own);
  // Random cells start F_t from colours of the look's own noise cells: one look.
  if (p.scene.init == InitMode::RandomCells) return "[" + looks.front() + "]";
  for (const Restyle& r : styles) {
    const std::string look =
        look_json(r.scene, std::string(r.style.name), r.style.description, finest, centre, moving);
    if (std::none_of(looks.begin(), looks.end(),
                     [&](const std::string& l) { return body(l) == body(look); }))
      looks.push_back(look);
  }
  std::string out = "[";
  for (const std::string& l : looks) out += (out.size() > 1 ? "," : "") + l;
  return out + "]";
}

}  // namespace

bool has_web_runtime() {
  return kWebRuntime != nullptr;
}

std::string web_page(const PreparedScene& p, WebPageReport* report, const WebPageLimits& limits) {
  const std::string what = "page of " + p.mesh_name;
  if (!has_web_runtime())
    throw InputError(what +
                     ": this ibfvs was built without the browser runtime (it needs node "
                     "and npm at build time, and web/node_modules from "
                     "scripts/install-deps.sh)");
  const TriMesh& mesh = *p.mesh;
  if (mesh.triangle_count() > limits.triangles)
    throw InputError(what + ": " + std::to_string(mesh.triangle_count()) +
                     " triangles, more than a page takes (" + std::to_string(limits.triangles) +
                     "); subdivide less or decimate the mesh");
  const std::size_t steps = std::max<std::size_t>(p.step_count, 1);
  // Every step's data: a surface that moves (its points at each step) or
  // changes (a step with triangles of its own is a mesh of its own in the
  // page: step_mesh, 1.. for meshes[0..]; 0 for the first step's).
  std::vector<StepData> data(steps);
  std::vector<int> step_mesh(steps, 0);
  bool moving = false;
  std::size_t other_meshes = 0, vectors_in_all = 0, triangles_in_all = mesh.triangle_count();
  for (std::size_t k = 0; k < steps; ++k) {
    if (p.step_data) data[k] = p.step_data(k);
    moving = moving || !data[k].positions.empty() || data[k].mesh;
    if (data[k].mesh) {
      step_mesh[k] = static_cast<int>(++other_meshes);
      vectors_in_all += data[k].mesh->vertex_count();
      triangles_in_all += data[k].mesh->triangle_count();
    }
  }
  vectors_in_all += steps * mesh.vertex_count();
  if (triangles_in_all > limits.triangles)
    throw InputError(what + ": " + std::to_string(triangles_in_all) +
                     " triangles over its steps' meshes, more than a page takes (" +
                     std::to_string(limits.triangles) + "); export fewer steps");
  if (vectors_in_all > limits.vectors)
    throw InputError(what + ": " + std::to_string(steps) + " time steps of " +
                     std::to_string(mesh.vertex_count()) + " vectors, more than a page takes (" +
                     std::to_string(limits.vectors) + " vectors); export fewer steps");
  // The first step's own data where it is not a series' (a steady scene).
  if (!p.step_data) data[0].field = p.field;

  const RenderSettings& s = p.settings;
  // The noise phases of the finest look (the default's 1-pixel cells; a
  // coarser grid takes the first of them).
  const std::vector<Restyle> styles = restyles(p);
  float finest_scale = s.noise.scale;
  for (const Restyle& r : styles)
    finest_scale = std::min(finest_scale, r.scene.settings.noise.scale);
  NoiseParams finest_noise = s.noise;
  finest_noise.scale = finest_scale;
  const NoiseGrid grid(p.width, p.height, finest_noise);
  const Bounds bounds = mesh_bounds(mesh);
  const Camera camera(bounds, p.camera, static_cast<float>(p.width) / static_cast<float>(p.height));
  // The box the positions are stored in: every step's points.
  glm::vec3 lo = bounds.min, hi = bounds.max;
  for (const StepData& d : data)
    for (const glm::vec3& r : d.mesh ? d.mesh->positions : d.positions) {
      lo = glm::min(lo, r);
      hi = glm::max(hi, r);
    }

  Block block;
  // Positions in 16 bits within the box; normals in 8-bit snorm; vectors in
  // half floats (they span decades: a fixed-point code would lose the slow).
  std::vector<std::uint16_t> positions;
  std::vector<std::int8_t> normals;
  std::vector<std::uint16_t> vectors;
  positions.reserve(mesh.positions.size() * 4);
  const glm::vec3 extent = hi - lo;
  // Four per vertex: the codec's stride is a multiple of 4 bytes.
  const auto put_vertex = [&](const glm::vec3& r, const glm::vec3& n, std::vector<std::uint16_t>& q,
                              std::vector<std::int8_t>& m) {
    for (int c = 0; c < 3; ++c) {
      const float t = extent[c] > 0.0f ? (r[c] - lo[c]) / extent[c] : 0.0f;
      q.push_back(static_cast<std::uint16_t>(std::lround(std::clamp(t, 0.0f, 1.0f) * 65535.0f)));
      m.push_back(snorm8(n[c]));
    }
    q.push_back(0);
    m.push_back(0);
  };
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    put_vertex(mesh.positions[i], mesh.normals[i], positions, normals);
  // Every time step of an unsteady field, one after the other (a step on
  // a mesh of its own: zeros here, its vectors with its mesh).
  const auto put_vectors = [](const std::vector<glm::vec3>& field,
                              std::vector<std::uint16_t>& out) {
    for (const glm::vec3& v : field) {
      for (int c = 0; c < 3; ++c) out.push_back(glm::packHalf1x16(v[c]));
      out.push_back(0);
    }
  };
  vectors.reserve(steps * mesh.positions.size() * 4);
  for (std::size_t step = 0; step < steps; ++step) {
    if (data[step].mesh)
      vectors.resize(vectors.size() + mesh.positions.size() * 4, 0);
    else
      put_vectors(data[step].field, vectors);
  }
  // The motion: the vertices whose stored point or normal differs from the
  // first step's at some step, and for each step theirs, a step the same as
  // the one before it stored once.
  std::string motion_json;
  if (moving) {
    std::vector<std::vector<std::uint16_t>> step_q(steps);
    std::vector<std::vector<std::int8_t>> step_n(steps);
    std::vector<std::uint8_t> moves(mesh.vertex_count(), 0);
    for (std::size_t k = 0; k < steps; ++k) {
      const StepData& d = data[k];
      const std::vector<glm::vec3>& r = d.positions.empty() ? mesh.positions : d.positions;
      const std::vector<glm::vec3>& n = d.normals.empty() ? mesh.normals : d.normals;
      step_q[k].reserve(r.size() * 4);
      step_n[k].reserve(r.size() * 4);
      for (std::size_t i = 0; i < r.size(); ++i) put_vertex(r[i], n[i], step_q[k], step_n[k]);
      for (std::size_t i = 0; i < r.size(); ++i)
        for (int c = 0; c < 3; ++c)
          moves[i] |= step_q[k][4 * i + c] != positions[4 * i + c] ||
                      step_n[k][4 * i + c] != normals[4 * i + c];
    }
    std::vector<std::uint32_t> movers;
    for (std::size_t i = 0; i < moves.size(); ++i)
      if (moves[i]) movers.push_back(static_cast<std::uint32_t>(i));
    std::vector<std::uint16_t> set_q;
    std::vector<std::int8_t> set_n;
    std::vector<int> set_of(steps, 0);
    std::vector<std::uint16_t> last_q;
    std::vector<std::int8_t> last_n;
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
    const std::size_t before = block.bytes().size();
    motion_json = ",\"motion\":{\"moving\":" + block.add(movers) +
                  ",\"positions\":" + block.add_vertices(set_q, 4) +
                  ",\"normals\":" + block.add_vertices(set_n, 4) +
                  ",\"sets\":" + json_numbers(set_of) + "}";
    if (report) {
      report->moving_vertices = movers.size();
      report->motion_sets = static_cast<std::size_t>(sets);
      report->motion = block.bytes().size() - before;
    }
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(mesh.triangles.size() * 3);
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) indices.push_back(static_cast<std::uint32_t>(t[c]));
  std::vector<std::uint16_t> phases;
  for (const float phi : grid.phases())
    phases.push_back(
        static_cast<std::uint16_t>(std::lround(std::clamp(phi, 0.0f, 1.0f) * 65535.0f)));
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
  std::string arrays =
      "{\"positions\":" +
      block.add_vertices(positions, 4,
                         ",\"min\":" + json_numbers(std::vector<float>{lo.x, lo.y, lo.z}) +
                             ",\"max\":" + json_numbers(std::vector<float>{hi.x, hi.y, hi.z})) +
      ",\"normals\":" + block.add_vertices(normals, 4) +
      ",\"vectors\":" + block.add_vertices(vectors, 4) +
      ",\"indices\":" + block.add_indices(indices, mesh.positions.size()) +
      ",\"phases\":" + block.add(phases) + ",\"color_map\":" + block.add(colours);
  if (s.use_color || s.use_beta) {
    // (colour, beta) per vertex: every step's where they change from step
    // to step (a transient result coloured by its own magnitude), as the
    // session sets them at each step; else the first step's.
    const auto put = [&](const std::vector<float>& colour, const std::vector<float>& beta,
                         std::vector<float>& out) {
      for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        out.push_back(colour.empty() ? 0.0f : colour[i]);
        out.push_back(beta.empty() ? 0.0f : beta[i]);
      }
    };
    std::vector<float> scalars;
    put(p.color_scalar, p.beta_scalar, scalars);
    const std::size_t first = scalars.size();
    bool changing = false;
    for (std::size_t k = 1; k < steps && p.step_data; ++k) {
      const StepData& d = data[k];  // a step on a mesh of its own: its scalars go with it
      put(d.mesh ? std::vector<float>() : d.color_scalar,
          d.mesh ? std::vector<float>() : d.beta_scalar, scalars);
      changing = changing || !std::equal(scalars.begin(), scalars.begin() + first,
                                         scalars.end() - static_cast<std::ptrdiff_t>(first));
    }
    if (!changing) scalars.resize(first);
    arrays +=
        ",\"scalars\":" +
        block.add_vertices(scalars, 2, ",\"steps\":" + std::to_string(scalars.size() / first));
  }
  // The steps whose triangles are their own (a changing mesh): each its
  // points and normals (in the same box), triangles, vectors and scalars.
  if (other_meshes > 0) {
    std::string meshes;
    for (std::size_t k = 0; k < steps; ++k) {
      if (!data[k].mesh) continue;
      const TriMesh& m = *data[k].mesh;
      std::vector<std::uint16_t> q, v;
      std::vector<std::int8_t> n;
      for (std::size_t i = 0; i < m.vertex_count(); ++i)
        put_vertex(m.positions[i], m.normals[i], q, n);
      put_vectors(data[k].field, v);
      std::vector<std::uint32_t> ids;
      for (const Triangle& t : m.triangles) ids.insert(ids.end(), t.begin(), t.end());
      meshes += std::string(meshes.empty() ? "" : ",") +
                "{\"vertex_count\":" + std::to_string(m.vertex_count()) +
                ",\"index_count\":" + std::to_string(ids.size()) +
                ",\"cull\":" + std::to_string(closed_orientation(m)) +
                ",\"positions\":" + block.add_vertices(q, 4) +
                ",\"normals\":" + block.add_vertices(n, 4) +
                ",\"vectors\":" + block.add_vertices(v, 4) +
                ",\"indices\":" + block.add_indices(ids, m.vertex_count());
      if (s.use_color || s.use_beta) {
        std::vector<float> sc;
        for (std::size_t i = 0; i < m.vertex_count(); ++i) {
          sc.push_back(data[k].color_scalar.empty() ? 0.0f : data[k].color_scalar[i]);
          sc.push_back(data[k].beta_scalar.empty() ? 0.0f : data[k].beta_scalar[i]);
        }
        meshes += ",\"scalars\":" + block.add_vertices(sc, 2);
      }
      meshes += "}";
    }
    arrays += ",\"meshes\":[" + meshes + "]";
    if (report) report->other_meshes = other_meshes;
  }
  if (const ImageU8& image = p.surface_image; !image.pixels.empty()) {
    // The surface colour (RGBA8, bottom row first as the GL texture takes
    // it), through the vertex codec: 4 bytes a pixel, deltas along the row.
    if (image.channels != 4) throw InputError(what + ": the surface image must be RGBA");
    arrays += ",\"surface_image\":" +
              block.add_vertices(image.pixels, 4,
                                 ",\"width\":" + std::to_string(image.width) +
                                     ",\"height\":" + std::to_string(image.height));
  }
  if (p.scene.init == InitMode::RandomCells) {
    // F_t's first colours, one per noise cell (IbfvsRenderer::
    // fill_texture_with_cell_colors): half floats, as F_t holds them.
    const int columns =
        static_cast<int>(std::ceil(static_cast<float>(p.width) / s.noise.scale)) + 1;
    const int rows = static_cast<int>(std::ceil(static_cast<float>(p.height) / s.noise.scale)) + 1;
    std::vector<std::uint16_t> cells;
    cells.reserve(static_cast<std::size_t>(columns) * rows * 4);
    for (std::uint64_t cell = 0; cell < static_cast<std::uint64_t>(columns) * rows; ++cell) {
      for (std::uint64_t c = 0; c < 3; ++c)
        cells.push_back(glm::packHalf1x16(hash_uniform(p.scene.seed, 3 * cell + c)));
      cells.push_back(0);
    }
    arrays += ",\"cells\":" + block.add(cells, ",\"columns\":" + std::to_string(columns) +
                                                   ",\"scale\":" + json_number(s.noise.scale));
  }
  arrays += motion_json + "}";

  const auto matrix = [](const glm::mat4& m) {
    return json_numbers(std::vector<float>(glm::value_ptr(m), glm::value_ptr(m) + 16));
  };
  const float diagonal = bounds.diagonal();
  const glm::vec3 centre = bounds.centre();
  const std::string name = std::filesystem::path(p.mesh_name).stem().string();
  // The lock (Session::advance): at that frame F_t stops and the camera
  // moves to the lock view.
  std::string lock = "null";
  if (p.lock_at >= 0) {
    const Camera lock_camera(bounds, p.lock_camera.value_or(p.camera),
                             static_cast<float>(p.width) / static_cast<float>(p.height));
    const glm::vec3 target = centre + p.lock_camera.value_or(p.camera).target;
    lock = "{\"frame\":" + std::to_string(p.lock_at) + ",\"view\":" + matrix(lock_camera.view()) +
           ",\"projection\":" + matrix(lock_camera.projection()) +
           ",\"target\":" + json_numbers(std::vector<float>{target.x, target.y, target.z}) + "}";
  }
  // The orbit (Camera::orbit): degrees a frame about the vertical through
  // the look-at point.
  std::string orbit = "null";
  if (p.scene.orbit != 0.0f) {
    const glm::vec3 up = p.camera.up;
    orbit = "{\"degrees\":" + json_number(p.scene.orbit) +
            ",\"up\":" + json_numbers(std::vector<float>{up.x, up.y, up.z}) + "}";
  }
  const glm::vec3 target = centre + p.camera.target;
  const std::string header =
      "{\"format\":\"ibfvs-page\",\"version\":2,\"name\":" +
      json_string(name.empty() ? "ibfvs" : name) + ",\"width\":" + std::to_string(p.width) +
      ",\"height\":" + std::to_string(p.height) +
      ",\"no_depth\":" + json_number(IbfvsRenderer::kNoDepth) +
      ",\"any_depth\":" + json_number(IbfvsRenderer::kAnyDepth) + ",\"lock\":" + lock +
      ",\"orbit\":" + orbit +
      ",\"target\":" + json_numbers(std::vector<float>{target.x, target.y, target.z}) +
      ",\"probe\":" + json_number(shaders::probe_length(diagonal)) +
      ",\"cull\":" + std::to_string(closed_orientation(mesh)) +
      ",\"stats\":{\"size\":" + std::to_string(display_stats_size(p.width, p.height)) +
      ",\"every\":" + std::to_string(IbfvsRenderer::kStatsEvery) +
      ",\"weight\":" + json_number(IbfvsRenderer::kStatsWeight) + "}" +
      ",\"view\":" + matrix(camera.view()) + ",\"projection\":" + matrix(camera.projection()) +
      ",\"centre\":" + json_numbers(std::vector<float>{centre.x, centre.y, centre.z}) +
      ",\"shaders\":{\"grid_vertex\":" +
      json_string(shaders::grid_vertex_source(shaders::Dialect::Es300)) +
      ",\"grid_fragment\":" + json_string(shaders::grid_fragment_source(shaders::Dialect::Es300)) +
      ",\"display_vertex\":" +
      json_string(shaders::display_vertex_source(shaders::Dialect::Es300)) + "},\"looks\":" +
      looks_json(p, styles, glm::ivec2(grid.columns(), grid.rows()), centre, moving) +
      ",\"vertex_count\":" + std::to_string(mesh.positions.size()) +
      ",\"steps\":" + std::to_string(steps) + ",\"step_mesh\":" + json_numbers(step_mesh) +
      ",\"frames_per_step\":" + std::to_string(p.scene.frames_per_step) +
      ",\"index_count\":" + std::to_string(indices.size()) + ",\"phase_size\":[" +
      std::to_string(grid.columns()) + "," + std::to_string(grid.rows()) + "]" +
      ",\"arrays\":" + arrays + "}";

  const std::string runtime = kWebRuntime;
  std::string page =
      "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>" +
      html_escape(name) +
      " - ibfvs</title>\n"
      "<style>body{font:14px system-ui,sans-serif;margin:1em;background:#fafafa;color:#222}"
      ".ibfvs-canvas{display:block;touch-action:none;cursor:grab;max-width:100%}"
      ".ibfvs-panel{margin:.5em 0;display:flex;gap:1em;flex-wrap:wrap;align-items:center}"
      ".ibfvs-message{padding:1em;border:1px solid #c33;background:#fee;max-width:40em}</style>\n"
      "</head>\n<body>\n<div id=\"ibfvs\"><p class=\"ibfvs-message\">This page shows an animated "
      "flow texture with WebGL2 and JavaScript; it needs both switched on.</p></div>\n"
      "<p>" +
      html_escape(name) +
      ": drag to turn, shift-drag to move, wheel to zoom, space to "
      "pause. Made by ibfvs.</p>\n"
      "<script type=\"application/json\" id=\"ibfvs-scene\">" +
      header +
      "</script>\n"
      "<script type=\"application/octet-stream\" id=\"ibfvs-data\">\n" +
      base64(block.bytes()) + "\n</script>\n<script>\n" + runtime +
      "\n</script>\n</body>\n</html>\n";
  if (report) {
    report->page = page.size();
    report->scene = block.bytes().size();
    report->runtime = runtime.size();
  }
  return page;
}

WebPageReport write_web_page(const PreparedScene& scene, const std::filesystem::path& path,
                             const WebPageLimits& limits) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".html" && ext != ".htm")
    throw InputError(path.string() + ": a page must be named NAME.html");
  WebPageReport report;
  const std::string page = web_page(scene, &report, limits);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(path.string() + ": cannot write");
  out.write(page.data(), static_cast<std::streamsize>(page.size()));
  if (!out) throw InputError(path.string() + ": cannot write (disk full?)");
  return report;
}

}  // namespace ibfvs
