#include "ibfvs/core/scene/mesh_source.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/mesh/dataset_io.h"
#include "ibfvs/core/mesh/gpu_prep.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/mesh/subdivision.h"
#include "ibfvs/core/support/data_paths.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/limits.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs {
namespace fs = std::filesystem;

namespace {

// Errors about a generated-mesh spec name the setting "mesh" and the spec.
[[noreturn]] void bad_spec(const std::string& spec, const std::string& problem) {
  throw SettingError("mesh", spec + ": " + problem);
}

int parse_int(const std::string& text, const std::string& spec, int lo, int hi) {
  try {
    return static_cast<int>(parse_integer(text, lo, hi));
  } catch (const InputError& e) {
    bad_spec(spec, e.what());
  }
}

std::vector<float> numbers(const std::string& text, const std::string& spec, std::size_t count = 0,
                           std::string_view form = "") {
  try {
    return parse_numbers(text, count, form);
  } catch (const InputError& e) {
    bad_spec(spec, e.what());
  }
}

// relief:FILE:VAR:LON0,LON1,LAT0,LAT1[:SCALE[:RESOLUTION]]: a height field of
// a gridded variable over a longitude/latitude box; x along longitude, -z
// along latitude, the longer side spanning [-1, 1], height = SCALE * value
// (default: the largest |value| lifts 0.1).
TriMesh make_relief(const std::string& spec) {
  const std::vector<std::string> parts = split_colons(spec);
  if (parts.size() < 4 || parts.size() > 6)
    bad_spec(spec, "expected relief:FILE:VAR:LON0,LON1,LAT0,LAT1[:SCALE[:RESOLUTION]]");
  const std::vector<float> box = numbers(parts[3], spec, 4);
  const float lon0 = box[0], lon1 = box[1], lat0 = box[2], lat1 = box[3];
  if (!(lon1 > lon0) || !(lat1 > lat0) || lat0 < -90 || lat1 > 90 || lon1 - lon0 > 360)
    bad_spec(spec, "the box needs LON0 < LON1 and -90 <= LAT0 < LAT1 <= 90");
  const LonLatGrid grid = read_lonlat_grid(parts[1], parts[2], 0);
  const int res = parts.size() > 5 ? parse_int(parts[5], spec, 1, 4096) : 256;
  const float span = std::max(lon1 - lon0, lat1 - lat0);
  const int nx = std::max(1, static_cast<int>(std::lround(res * (lon1 - lon0) / span)));
  const int ny = std::max(1, static_cast<int>(std::lround(res * (lat1 - lat0) / span)));
  std::vector<float> values;
  float largest = 0.0f;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const float v = grid.sample(lon0 + (lon1 - lon0) * i / nx, lat0 + (lat1 - lat0) * j / ny);
      values.push_back(v);
      if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
    }
  float scale = largest > 0.0f ? 0.1f / largest : 0.0f;
  if (parts.size() > 4 && !parts[4].empty()) {
    std::size_t used = 0;
    try {
      scale = std::stof(parts[4], &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != parts[4].size() || !std::isfinite(scale))
      bad_spec(spec, "the scale '" + parts[4] + "' is not a number");
  }
  TriMesh m;
  std::vector<float>& relief = m.scalars[parts[2]];
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const float v = values[static_cast<std::size_t>(j) * (nx + 1) + i];
      const float h = std::isfinite(v) ? v : 0.0f;
      m.positions.emplace_back((2.0f * i / nx - 1.0f) * (lon1 - lon0) / span, scale * h,
                               -(2.0f * j / ny - 1.0f) * (lat1 - lat0) / span);
      relief.push_back(v);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const auto id = [&](int a, int b) { return static_cast<std::uint32_t>(b * (nx + 1) + a); };
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  compute_vertex_normals(m);
  return m;
}

TriMesh make_landscape(const std::string& spec) {
  const std::vector<std::string> parts = split_colons(spec);
  if (parts[0] != "landscape" || parts.size() > 4)
    bad_spec(spec, "expected landscape[:SEED[:CONTROLS[:RESOLUTION]]]");
  // landscape:FILE[:RESOLUTION]: the control heights given, one row per line.
  std::error_code ec;
  if (parts.size() > 1 && fs::is_regular_file(parts[1], ec)) {
    if (parts.size() > 3) bad_spec(spec, "expected landscape:FILE[:RESOLUTION]");
    std::ifstream in(parts[1]);
    std::vector<float> controls;
    int columns = -1, rows = 0;
    for (std::string line; std::getline(in, line);) {
      if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
      std::istringstream numbers(line);
      int n = 0;
      for (std::string word; numbers >> word; ++n) {
        try {
          controls.push_back(static_cast<float>(parse_number(word)));
        } catch (const InputError& e) {
          throw InputError(parts[1] + ": line " + std::to_string(rows + 1) + ": " + e.what());
        }
      }
      if (columns >= 0 && n != columns)
        throw InputError(parts[1] + ": every row of control heights needs " +
                         std::to_string(columns) + " numbers, a row has " + std::to_string(n));
      columns = n;
      ++rows;
    }
    const int resolution = parts.size() > 2 ? parse_int(parts[2], spec, 1, 4096) : 256;
    try {
      return make_bspline_height_field(controls, std::max(columns, 0), rows, resolution);
    } catch (const InputError& e) {
      throw InputError(parts[1] + ": " + e.what());
    }
  }
  const int seed = parts.size() > 1 ? parse_int(parts[1], spec, 0, 1 << 30) : 1;
  const int controls = parts.size() > 2 ? parse_int(parts[2], spec, 4, 256) : 8;
  const int resolution = parts.size() > 3 ? parse_int(parts[3], spec, 1, 4096) : 256;
  return make_bspline_height_field(
      random_controls(controls, controls, 0.3f, static_cast<std::uint32_t>(seed)), controls,
      controls, resolution);
}

// torus[:R,r]: the torus around the Y axis (lying flat, +Y up), centre-line
// radius R and tube radius r (default 1, 0.4), 160 x 64 cells.
TriMesh make_torus_spec(const std::string& spec) {
  const std::vector<std::string> parts = split_colons(spec);
  if (parts[0] != "torus" || parts.size() > 2) bad_spec(spec, "expected torus[:R,r]");
  const std::vector<float> radii =
      parts.size() > 1 ? numbers(parts[1], spec, 2, "R,r") : std::vector<float>{1.0f, 0.4f};
  if (!(radii[1] > 0) || !(radii[0] > radii[1])) bad_spec(spec, "the radii need R > r > 0");
  return make_torus(radii[0], radii[1], 160, 64);
}

// globe[:LEVEL]: the unit sphere, an icosahedron subdivided LEVEL times (default 6).
TriMesh make_globe_spec(const std::string& spec) {
  const std::size_t colon = spec.find(':');
  if (spec.substr(0, colon) != "globe") bad_spec(spec, "expected globe[:LEVEL]");
  return make_globe(colon == std::string::npos ? 6 : parse_int(spec.substr(colon + 1), spec, 0, 8));
}

// cylinder[:RADIUS,LENGTH[,COUNT]]: COUNT open cylinders (default one, radius
// 0.3, length 3) with their axes along X, stacked along Y three radii apart.
TriMesh make_cylinders_spec(const std::string& spec) {
  const std::vector<std::string> parts = split_colons(spec);
  if (parts[0] != "cylinder" || parts.size() > 2)
    bad_spec(spec, "expected cylinder[:RADIUS,LENGTH[,COUNT]]");
  std::vector<float> p = {0.3f, 3.0f, 1.0f};
  if (parts.size() > 1) {
    const std::vector<float> given = numbers(parts[1], spec);
    if (given.size() < 2 || given.size() > 3)
      bad_spec(spec, "expected cylinder[:RADIUS,LENGTH[,COUNT]]");
    std::copy(given.begin(), given.end(), p.begin());
  }
  const float r = p[0], length = p[1];
  if (!(r > 0) || !(length > 0) || p[2] < 1 || p[2] > 16 || p[2] != std::floor(p[2]))
    bad_spec(spec, "needs RADIUS > 0, LENGTH > 0 and COUNT in 1..16");
  const int count = static_cast<int>(p[2]);
  constexpr int kSegments = 128;
  const int rings = std::clamp(
      static_cast<int>(std::ceil(length / (2.0f * std::numbers::pi_v<float> * r / kSegments))), 1,
      4096);
  const TriMesh one = make_cylinder(r, length, kSegments, rings);
  TriMesh m;
  for (int c = 0; c < count; ++c) {
    const float y = 3.0f * r * (static_cast<float>(c) - 0.5f * static_cast<float>(count - 1));
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (std::size_t i = 0; i < one.positions.size(); ++i) {
      // Y axis -> X axis: (x, y, z) -> (y, -x, z) is a rotation about Z.
      const glm::vec3 q = one.positions[i], n = one.normals[i];
      m.positions.emplace_back(q.y, -q.x + y, q.z);
      m.normals.emplace_back(n.y, -n.x, n.z);
    }
    for (const Triangle& t : one.triangles)
      m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return m;
}

// The last run of digits in a file name (for ordering a numbered series), or
// -1 when it has none.
long long last_number(const std::string& name) {
  const std::size_t end = name.find_last_of("0123456789");
  if (end == std::string::npos) return -1;
  std::size_t begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(name[begin - 1]))) --begin;
  const std::string digits = name.substr(begin, std::min<std::size_t>(end - begin + 1, 18));
  return std::stoll(digits);
}

// The files of a numbered series `dir/pattern`, ordered by their numbers.
std::vector<std::string> series_files(const std::string& path) {
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  const std::string pattern = p.filename().string();
  if (p.parent_path().string().find('*') != std::string::npos)
    throw InputError(path + ": only the file name of a series may hold '*'");
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec) && glob_match(pattern, it->path().filename().string()))
      names.push_back(it->path().filename().string());
  if (names.empty()) throw InputError(path + ": no file matches");
  std::stable_sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
    const long long na = last_number(a), nb = last_number(b);
    return na != nb ? na < nb : a < b;
  });
  std::vector<std::string> files;
  for (const std::string& n : names) files.push_back((dir / n).string());
  return files;
}

// "1.52 billion", "380 million", "92,864".
std::string format_count(double n) {
  char text[48];
  if (n >= 1e9)
    std::snprintf(text, sizeof text, "%.3g billion", n / 1e9);
  else if (n >= 1e6)
    std::snprintf(text, sizeof text, "%.3g million", n / 1e6);
  else
    std::snprintf(text, sizeof text, "%.0f", n);
  return text;
}

// After reading: subdivision (errors name the mesh) and the GPU's vertex order.
void finish_loaded(LoadedMesh& out, int subdivide, bool gpu_order) {
  out.file_vertices = out.mesh.vertex_count();
  out.file_topology = topology_hash(out.mesh);
  if (subdivide > 0) {
    // Refused before subdividing: each level makes four triangles of one.
    const double triangles = subdivided_triangles(out.mesh.triangle_count(), subdivide);
    if (mesh_bytes(triangles) > static_cast<double>(memory_limit()) && memory_limit() > 0) {
      int fits = subdivide;
      while (fits > 0 && mesh_bytes(subdivided_triangles(out.mesh.triangle_count(), fits)) >
                             static_cast<double>(memory_limit()))
        --fits;
      try {
        check_memory(mesh_bytes(triangles), out.name + " subdivided " + std::to_string(subdivide) +
                                                " times (" + format_count(triangles) +
                                                " triangles)");
      } catch (const InputError& e) {
        std::string problem = e.what();
        problem += "; at most ";
        problem += std::to_string(fits);
        problem += fits == 1 ? " level fits" : " levels fit";
        throw SettingError("subdivide", problem);
      }
    }
    try {
      out.mesh = loop_subdivide(out.mesh, subdivide);
    } catch (const InputError& e) {
      throw InputError(out.name + ": " + e.what());
    }
  }
  if (gpu_order) out.vertex_order = optimize_for_gpu(out.mesh);
}

}  // namespace

TriMesh read_any_mesh(const std::string& path, const std::vector<std::string>& blocks,
                      std::vector<std::string>* warnings) {
  if (is_dataset_path(path)) {
    Dataset d = read_dataset({path, blocks});
    if (warnings) warnings->insert(warnings->end(), d.warnings.begin(), d.warnings.end());
    return std::move(d.mesh);
  }
  if (!blocks.empty())
    throw SettingError("blocks", path + ": has no blocks (only .vtm files and OpenFOAM cases do)");
  MeshReadReport report;
  TriMesh mesh = read_mesh(path, &report);
  if (warnings) warnings->insert(warnings->end(), report.warnings.begin(), report.warnings.end());
  return mesh;
}

namespace {

// The generated surfaces, by the prefix that names one (a file of that name
// wins): each checks the rest of its text.
struct Generator {
  std::string_view prefix;
  TriMesh (*make)(const std::string& spec);
  bool landscape;  // a height field: its default field runs downhill
};
constexpr Generator kGenerators[] = {
    {"globe", make_globe_spec, false},   {"relief:", make_relief, true},
    {"torus", make_torus_spec, false},   {"cylinder", make_cylinders_spec, false},
    {"landscape", make_landscape, true},
};

const Generator* generator_for(const std::string& path) {
  for (const Generator& g : kGenerators)
    if (path.rfind(g.prefix, 0) == 0) return &g;
  return nullptr;
}

}  // namespace

LoadedMesh load_mesh(const std::string& path, int subdivide, bool gpu_order,
                     const std::vector<std::string>& blocks) {
  LoadedMesh out;
  out.demo = path.empty();
  if (out.demo) {
    std::optional<fs::path> demo = find_data_file("meshes/bunny00.off");
    if (!demo) demo = find_data_file("meshes/cow.off");
    if (demo) {
      out.mesh = read_mesh(*demo);
      out.name = demo->filename().string();
    } else {
      out.warnings.push_back("the fetched meshes are missing (" + (data_dir() / "meshes").string() +
                             "); using a procedural torus instead. Run scripts/fetch_data.sh "
                             "for the bunny.");
      out.mesh = make_torus(1.0f, 0.4f, 160, 64);
      out.name = "procedural torus";
    }
  } else if (const Generator* g = generator_for(path); g && !fs::exists(path)) {
    out.mesh = g->make(path);
    out.name = path;
    out.generated_landscape = g->landscape;
  } else if (path.find('*') != std::string::npos && !fs::exists(path)) {
    // A numbered series: the first file's mesh, every file's arrays a step.
    const std::vector<std::string> files = series_files(path);
    out.mesh = read_any_mesh(files[0], blocks, &out.warnings);
    out.name = path;
    if (files.size() > 1) {
      for (std::size_t k = 0; k < files.size(); ++k)
        out.step_times.push_back(static_cast<double>(k));
      // Each file its own surface: the points may move and the triangles
      // change from file to file (scene_prep takes either on).
      out.read_step = [files, blocks](std::size_t k) { return read_any_mesh(files.at(k), blocks); };
    }
  } else if (is_dataset_path(path)) {
    Dataset d = read_dataset({path, blocks});
    out.mesh = std::move(d.mesh);
    out.warnings = std::move(d.warnings);
    out.name = path;
    if (d.times.size() > 1) {
      out.step_times = std::move(d.times);
      out.read_step = std::move(d.step);
    }
  } else {
    out.mesh = read_any_mesh(path, blocks, &out.warnings);
    out.name = path;
  }
  finish_loaded(out, subdivide, gpu_order);
  return out;
}

LoadedMesh load_mesh(TriMesh mesh, const std::string& name, int subdivide, bool gpu_order) {
  LoadedMesh out;
  validate_mesh(mesh, name);
  if (mesh.normals.size() != mesh.vertex_count()) compute_vertex_normals(mesh);
  out.mesh = std::move(mesh);
  out.name = name;
  finish_loaded(out, subdivide, gpu_order);
  return out;
}

}  // namespace ibfvs
