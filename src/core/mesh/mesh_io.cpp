#include "ibfvs/core/mesh/mesh_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <new>
#include <optional>
#include <set>
#include <sstream>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <glm/geometric.hpp>

#include "ibfvs/core/mesh/mesh_bytes.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"
#include "ibfvs/core/support/isolation.h"
#include "openmesh_errors.h"

namespace ibfvs {
namespace {

using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<>;
namespace fs = std::filesystem;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// Counts the file declares, where the format declares them (OFF, PLY).
struct DeclaredCounts {
  std::optional<std::size_t> vertices;
  std::optional<std::size_t> faces;
  bool ascii = true;
};

[[noreturn]] void fail(const fs::path& path, const std::string& problem) {
  throw InputError(path.string() + ": " + problem);
}

std::size_t parse_count(const fs::path& path, const std::string& token, const char* what) {
  if (token.empty() || !std::all_of(token.begin(), token.end(),
                                    [](unsigned char c) { return std::isdigit(c) != 0; }))
    fail(path, std::string("bad ") + what + " count '" + token + "' in the header");
  try {
    return std::stoull(token);
  } catch (const std::exception&) {
    fail(path, std::string("bad ") + what + " count '" + token + "' in the header");
  }
}

DeclaredCounts off_header(const fs::path& path, std::istream& in) {
  DeclaredCounts counts;
  std::string magic;
  in >> magic;
  if (magic.find("OFF") == std::string::npos)
    fail(path, "not an OFF file (the first word is not OFF)");
  if (magic.find('4') != std::string::npos || magic.find('n') == 0)
    return counts;  // 4D or n-dimensional variants: leave the checks to the reader
  std::string rest;
  std::getline(in, rest);
  if (rest.find("BINARY") != std::string::npos) {
    counts.ascii = false;
    return counts;
  }
  std::vector<std::string> tokens;
  std::istringstream head(rest);
  for (std::string t; head >> t;) tokens.push_back(t);
  // The counts may be on the magic line or on the next non-comment line.
  while (tokens.size() < 2) {
    std::string line;
    if (!std::getline(in, line)) fail(path, "truncated OFF header (no vertex and face counts)");
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    for (std::string t; ls >> t;) tokens.push_back(t);
  }
  counts.vertices = parse_count(path, tokens[0], "vertex");
  counts.faces = parse_count(path, tokens[1], "face");
  // OpenMesh reads one vertex, then one face, per line, and makes up what a
  // missing line would hold (garbage, differing from build to build): fewer
  // data lines than that is a truncated file.
  std::size_t data_lines = 0;
  for (std::string line; std::getline(in, line);) {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#') ++data_lines;
  }
  if (data_lines < *counts.vertices + *counts.faces)
    fail(path, "truncated: the header declares " + std::to_string(*counts.vertices) +
                   " vertices and " + std::to_string(*counts.faces) + " faces but only " +
                   std::to_string(data_lines) + " lines of data follow");
  return counts;
}

DeclaredCounts ply_header(const fs::path& path, std::istream& in) {
  DeclaredCounts counts;
  std::string line;
  std::getline(in, line);
  if (lower(line).rfind("ply", 0) != 0) fail(path, "not a PLY file (the first line is not 'ply')");
  bool ended = false;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key == "format") {
      std::string fmt;
      ls >> fmt;
      counts.ascii = fmt == "ascii";
    } else if (key == "element") {
      std::string name, n;
      ls >> name >> n;
      if (name == "vertex") counts.vertices = parse_count(path, n, "vertex");
      if (name == "face") counts.faces = parse_count(path, n, "face");
    } else if (key == "end_header") {
      ended = true;
      break;
    }
  }
  if (!ended) fail(path, "truncated PLY header (no end_header)");
  if (!counts.vertices) fail(path, "the PLY header declares no vertex element");
  return counts;
}

bool is_non_finite_token(std::string t) {
  t = lower(t);
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) t.erase(0, 1);
  return t.rfind("nan", 0) == 0 || t == "inf" || t == "infinity";
}

// iostream extraction stops at a "nan" token and the readers then misparse the
// rest; scan the numbers of ASCII files first so the error says what is wrong.
void reject_non_finite_text(const fs::path& path) {
  std::ifstream in(path);
  std::size_t line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    for (std::string t; ls >> t;)
      if (is_non_finite_token(t))
        fail(path, "line " + std::to_string(line_no) + " holds a non-finite number '" + t + "'");
  }
}

bool stl_is_ascii(const fs::path& path, std::uintmax_t size) {
  std::ifstream in(path, std::ios::binary);
  char head[5] = {};
  in.read(head, 5);
  if (std::string(head, 5) != "solid") return false;
  // Binary STLs may start with "solid" too; their size is 84 + 50 * count.
  if (size >= 84) {
    in.seekg(80);
    std::uint32_t n = 0;
    in.read(reinterpret_cast<char*>(&n), 4);
    if (84 + 50 * static_cast<std::uintmax_t>(n) == size) return false;
  }
  return true;
}

// Copies a scalar vertex property of OpenMesh vertices `kept` (in that order).
template <class T>
bool copy_scalar_property(OpenMesh::BaseProperty* base, const std::vector<std::size_t>& kept,
                          std::vector<float>& out) {
  auto* prop = dynamic_cast<OpenMesh::PropertyT<T>*>(base);
  if (!prop) return false;
  out.resize(kept.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>((*prop)[kept[i]]);
  return true;
}

bool copy_any_scalar(OpenMesh::BaseProperty* base, const std::vector<std::size_t>& kept,
                     std::vector<float>& out) {
  return copy_scalar_property<float>(base, kept, out) ||
         copy_scalar_property<double>(base, kept, out) ||
         copy_scalar_property<int>(base, kept, out) ||
         copy_scalar_property<unsigned int>(base, kept, out) ||
         copy_scalar_property<short>(base, kept, out) ||
         copy_scalar_property<unsigned short>(base, kept, out) ||
         copy_scalar_property<signed char>(base, kept, out) ||
         copy_scalar_property<unsigned char>(base, kept, out) ||
         copy_scalar_property<char>(base, kept, out);
}

// OpenMesh's importer gives a face it cannot join to its manifold
// connectivity (a duplicate or reversed face, a third face on an edge) fresh
// copies of its vertices, marked non-manifold; the copies carry no custom
// properties. Map each copy back to the vertex it copies (same point), so the
// face keeps its data and no vertex is duplicated. Returns the number of faces
// that needed it; fills `kept` (OpenMesh indices of our vertices, in order)
// and `new_index` (our index of every OpenMesh vertex).
std::size_t merge_nonmanifold_copies(PolyMesh& pm, std::vector<std::size_t>& kept,
                                     std::vector<std::uint32_t>& new_index) {
  const std::size_t nv = pm.n_vertices();
  kept.clear();
  kept.reserve(nv);
  new_index.assign(nv, 0);
  std::map<std::array<float, 3>, std::uint32_t> originals;
  std::size_t copies = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    const PolyMesh::VertexHandle vh(static_cast<int>(v));
    const auto& p = pm.point(vh);
    const std::array<float, 3> key{p[0], p[1], p[2]};
    if (pm.status(vh).fixed_nonmanifold()) {
      if (const auto it = originals.find(key); it != originals.end()) {
        new_index[v] = it->second;
        ++copies;
        continue;
      }
    }
    new_index[v] = static_cast<std::uint32_t>(kept.size());
    originals.emplace(key, new_index[v]);
    kept.push_back(v);
  }
  return copies;
}

// OpenMesh's OFF reader does not skip comments; strip them (from '#' to the
// end of the line) so that commented files from other tools read.
std::string off_without_comments(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    out += line;
    out += '\n';
  }
  return out;
}

// What OpenMesh makes of the file, with our checks of its answer: runs in
// the reading child (read_mesh).
TriMesh read_here(const fs::path& path, std::uintmax_t size, MeshReadReport& report) {
  const std::string ext = lower_extension(path);
  DeclaredCounts declared;
  {
    std::ifstream in(path, std::ios::binary);
    if (ext == ".off") {
      declared = off_header(path, in);
    } else if (ext == ".ply") {
      declared = ply_header(path, in);
    } else if (ext == ".stl") {
      declared.ascii = stl_is_ascii(path, size);
      if (!declared.ascii && (size < 84 || (size - 84) % 50 != 0))
        fail(path, "truncated or malformed binary STL (size is not 84 + 50 * triangles)");
    }
  }
  // A count larger than the bytes that could hold it is a corrupt header; refuse
  // it before the reader tries to allocate it.
  if ((declared.vertices && *declared.vertices > size) ||
      (declared.faces && *declared.faces > size))
    fail(path, "the header declares " + std::to_string(declared.vertices.value_or(0)) +
                   " vertices and " + std::to_string(declared.faces.value_or(0)) +
                   " faces, more than a file of " + std::to_string(size) + " bytes can hold");
  if (declared.ascii) reject_non_finite_text(path);
  const std::string off_text = ext == ".off" && declared.ascii ? off_without_comments(path) : "";

  PolyMesh pm;
  pm.request_vertex_normals();
  pm.request_vertex_status();
  OpenMesh::IO::Options opt = OpenMesh::IO::Options::Custom;
  opt += OpenMesh::IO::Options::VertexNormal;
  std::vector<std::string> messages;
  bool ok = false;
  {
    OmErrCapture capture;
    try {
      if (ext == ".off" && declared.ascii) {
        std::istringstream text(off_text);
        ok = OpenMesh::IO::read_mesh(pm, text, ".off", opt);
      } else {
        ok = OpenMesh::IO::read_mesh(pm, path.string(), opt);
      }
    } catch (const std::bad_alloc&) {
      fail(path, "malformed file (the reader ran out of memory on its counts)");
    } catch (const std::exception& e) {
      fail(path, std::string("malformed file: ") + e.what());
    }
    messages = capture.lines();
  }
  const auto has = [&](const char* needle) {
    return std::any_of(messages.begin(), messages.end(),
                       [&](const std::string& m) { return m.find(needle) != std::string::npos; });
  };
  if (has("invalid vertex index"))
    fail(path, "truncated or malformed: a face references a vertex index out of range");
  if (!ok) {
    const std::string why = messages.empty() ? "the reader rejected it" : messages.front();
    fail(path, "cannot parse the mesh: " + why);
  }
  for (const std::string& m : messages)
    if (m.find("equal vertices") != std::string::npos) ++report.faces_skipped;

  if (declared.vertices && pm.n_vertices() < *declared.vertices)
    fail(path, "truncated or malformed: the header declares " + std::to_string(*declared.vertices) +
                   " vertices but " + std::to_string(pm.n_vertices()) + " were read");
  if (declared.faces && pm.n_faces() + report.faces_skipped < *declared.faces)
    fail(path, "truncated or malformed: the header declares " + std::to_string(*declared.faces) +
                   " faces but " + std::to_string(pm.n_faces()) + " were read");
  if (pm.n_faces() == 0) fail(path, "no faces could be read: not a surface mesh");

  std::vector<std::size_t> kept;
  std::vector<std::uint32_t> new_index;
  const std::size_t copies = merge_nonmanifold_copies(pm, kept, new_index);
  TriMesh mesh;
  const std::size_t nv = kept.size();
  mesh.positions.resize(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    const auto& p = pm.point(PolyMesh::VertexHandle(static_cast<int>(kept[i])));
    mesh.positions[i] = glm::vec3(p[0], p[1], p[2]);
  }
  // Fan triangulation of convex polygons keeps the vertex order and needs no
  // geometry; non-convex polygons are rare in the formats we read.
  mesh.triangles.reserve(pm.n_faces());
  for (const auto fh : pm.faces()) {
    std::vector<std::uint32_t> ids;
    for (const auto vh : pm.fv_range(fh))
      ids.push_back(new_index[static_cast<std::size_t>(vh.idx())]);
    if (ids.size() > 3) ++report.polygons_triangulated;
    for (std::size_t k = 1; k + 1 < ids.size(); ++k)
      mesh.triangles.push_back({ids[0], ids[k], ids[k + 1]});
  }

  // Per-vertex properties from the file (PLY custom properties).
  static const std::set<std::string> kStandard = {
      "x",    "y",     "z", "nx", "ny", "nz", "red",       "green",
      "blue", "alpha", "u", "v",  "s",  "t",  "texture_u", "texture_v"};
  std::map<std::string, std::vector<float>> props;
  for (auto it = pm.vprops_begin(); it != pm.vprops_end(); ++it) {
    OpenMesh::BaseProperty* base = *it;
    if (!base) continue;
    const std::string& name = base->name();
    if (name.empty() || name[0] == '<' || name.rfind("v:", 0) == 0 || kStandard.count(name))
      continue;
    std::vector<float> values;
    if (copy_any_scalar(base, kept, values)) props[name] = std::move(values);
  }
  if (props.count("vx") && props.count("vy") && props.count("vz")) {
    mesh.vectors.resize(nv);
    for (std::size_t i = 0; i < nv; ++i)
      mesh.vectors[i] = glm::vec3(props["vx"][i], props["vy"][i], props["vz"][i]);
    props.erase("vx");
    props.erase("vy");
    props.erase("vz");
  }
  mesh.scalars = std::move(props);

  validate_mesh(mesh, path.string());
  report.degenerate_removed = remove_degenerate_triangles(mesh);
  if (mesh.triangles.empty()) fail(path, "every triangle is degenerate (zero area)");

  if (opt.vertex_has_normal()) {
    report.normals_from_file = true;
    mesh.normals.resize(nv);
    for (std::size_t i = 0; i < nv; ++i) {
      const auto& n = pm.normal(PolyMesh::VertexHandle(static_cast<int>(kept[i])));
      const glm::vec3 v(n[0], n[1], n[2]);
      const float len = glm::length(v);
      mesh.normals[i] = (len > 0.0f && std::isfinite(len)) ? v / len : glm::vec3(0.0f);
    }
    // A file with zero or broken normals gets computed ones instead.
    if (std::any_of(mesh.normals.begin(), mesh.normals.end(),
                    [](const glm::vec3& n) { return n == glm::vec3(0.0f); })) {
      report.normals_from_file = false;
      compute_vertex_normals(mesh);
    }
  } else {
    compute_vertex_normals(mesh);
  }

  std::vector<bool> used(nv, false);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t i : t) used[i] = true;
  report.unreferenced_vertices =
      static_cast<std::size_t>(std::count(used.begin(), used.end(), false));

  const std::string name = path.string();
  if (copies)
    report.warnings.push_back(name + ": " + std::to_string(copies) +
                              " vertex uses are on non-manifold or duplicate faces (kept)");
  if (report.faces_skipped)
    report.warnings.push_back(name + ": skipped " + std::to_string(report.faces_skipped) +
                              " faces with repeated vertices");
  if (report.degenerate_removed)
    report.warnings.push_back(name + ": dropped " + std::to_string(report.degenerate_removed) +
                              " zero-area triangles");
  return mesh;
}

void put_report(ByteWriter& out, const MeshReadReport& r) {
  for (const std::size_t n :
       {r.polygons_triangulated, r.faces_skipped, r.degenerate_removed, r.unreferenced_vertices})
    out.put<std::uint64_t>(n);
  out.put<char>(r.normals_from_file ? 1 : 0);
  out.put(r.warnings);
}

MeshReadReport get_report(ByteReader& in) {
  MeshReadReport r;
  for (std::size_t* n : {&r.polygons_triangulated, &r.faces_skipped, &r.degenerate_removed,
                         &r.unreferenced_vertices})
    *n = static_cast<std::size_t>(in.get<std::uint64_t>());
  r.normals_from_file = in.get<char>() != 0;
  r.warnings = in.get_strings();
  return r;
}

}  // namespace

TriMesh read_mesh(const fs::path& path, MeshReadReport* report_out) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(path, "no such file");
  if (!fs::is_regular_file(path, ec)) fail(path, "not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) fail(path, "cannot read the file size: " + ec.message());
  if (size == 0) fail(path, "the file is empty");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) fail(path, "cannot open the file for reading");
  }
  const std::string ext = lower_extension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl")
    fail(path, "unknown mesh format '" + ext + "' (expected .off, .obj, .ply or .stl)");
  // OpenMesh reads in a child process: a crash, a runaway allocation or a
  // loop in it is one error line (support/isolation.h), and nothing of ours
  // re-parses the file in front of it.
  const IsolatedBytes bytes =
      run_isolated(path.string(), "OpenMesh's reader", [&](ByteWriter& out) {
        MeshReadReport report;
        const TriMesh mesh = read_here(path, size, report);
        put_mesh(out, mesh);
        put_report(out, report);
      });
  ByteReader in(bytes.view(), path.string());
  TriMesh mesh = get_mesh(in);
  MeshReadReport report = get_report(in);
  if (report_out) *report_out = std::move(report);
  return mesh;
}

void write_obj_textured(const TriMesh& mesh, const std::vector<glm::vec2>& uv, const fs::path& path,
                        const std::string& texture_file) {
  if (uv.size() != mesh.vertex_count())
    throw InputError(path.string() + ": one texture coordinate per vertex is needed");
  fs::path mtl = path;
  mtl.replace_extension(".mtl");
  {
    std::ofstream m(mtl);
    if (!m) throw InputError(mtl.string() + ": cannot open for writing");
    m << "# written by ibfvs\nnewmtl ibfvs_texture\nKa 1 1 1\nKd 1 1 1\nKs 0 0 0\nillum 1\n"
      << "map_Kd " << texture_file << "\n";
    if (!m) throw InputError(mtl.string() + ": write failed");
  }
  std::ofstream out(path);
  if (!out) throw InputError(path.string() + ": cannot open for writing");
  const bool has_n = mesh.normals.size() == mesh.vertex_count();
  out << "# written by ibfvs: the locked IBFVS texture as an ordinary texture map\n"
      << "mtllib " << mtl.filename().string() << "\nusemtl ibfvs_texture\n";
  for (const glm::vec3& p : mesh.positions) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
  for (const glm::vec2& t : uv) out << "vt " << t.x << " " << t.y << "\n";
  if (has_n)
    for (const glm::vec3& n : mesh.normals) out << "vn " << n.x << " " << n.y << " " << n.z << "\n";
  for (const Triangle& t : mesh.triangles) {
    out << "f";
    for (const std::uint32_t i : t) {
      const std::uint32_t k = i + 1;
      out << " " << k << "/" << k;
      if (has_n) out << "/" << k;
    }
    out << "\n";
  }
  if (!out) throw InputError(path.string() + ": write failed");
}

void write_ply(const TriMesh& mesh, const fs::path& path, bool binary) {
  PendingFile pending(path);  // whole or not at all
  std::ofstream out(pending.temporary(), std::ios::binary);
  if (!out) throw InputError(path.string() + ": cannot open for writing");
  const bool has_n = mesh.normals.size() == mesh.positions.size();
  const bool has_v = mesh.vectors.size() == mesh.positions.size();
  out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\n"
      << "comment written by ibfvs\n"
      << "element vertex " << mesh.positions.size() << "\n"
      << "property float x\nproperty float y\nproperty float z\n";
  if (has_n) out << "property float nx\nproperty float ny\nproperty float nz\n";
  if (has_v) out << "property float vx\nproperty float vy\nproperty float vz\n";
  for (const auto& [name, values] : mesh.scalars) out << "property float " << name << "\n";
  out << "element face " << mesh.triangles.size() << "\n"
      << "property list uchar int vertex_indices\nend_header\n";
  std::vector<float> row;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    row.clear();
    const auto push = [&](const glm::vec3& v) { row.insert(row.end(), {v.x, v.y, v.z}); };
    push(mesh.positions[i]);
    if (has_n) push(mesh.normals[i]);
    if (has_v) push(mesh.vectors[i]);
    for (const auto& [name, values] : mesh.scalars) row.push_back(values[i]);
    if (binary) {
      out.write(reinterpret_cast<const char*>(row.data()),
                static_cast<std::streamsize>(row.size() * sizeof(float)));
    } else {
      for (std::size_t k = 0; k < row.size(); ++k) out << (k ? " " : "") << row[k];
      out << "\n";
    }
  }
  for (const Triangle& t : mesh.triangles) {
    if (binary) {
      const unsigned char three = 3;
      const std::int32_t ids[3] = {static_cast<std::int32_t>(t[0]), static_cast<std::int32_t>(t[1]),
                                   static_cast<std::int32_t>(t[2])};
      out.write(reinterpret_cast<const char*>(&three), 1);
      out.write(reinterpret_cast<const char*>(ids), sizeof ids);
    } else {
      out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    }
  }
  out.close();
  if (!out) throw InputError(path.string() + ": write failed");
  pending.commit();
}

}  // namespace ibfvs
