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

[[noreturn]] void fail(const fs::path& path, const std::string& problem) {
  throw InputError(path.string() + ": " + problem);
}

bool is_non_finite_token(std::string t) {
  t = lower(t);
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) t.erase(0, 1);
  return t.rfind("nan", 0) == 0 || t == "inf" || t == "infinity";
}

// Where OpenMesh's reader stopped in `text` (its stream failed there): the
// line, and the word it could not take, for the message. Nothing is parsed
// but that word: the reader's own state says the file is bad.
std::string stopped_at(const std::string& text, std::size_t at, bool ended) {
  at = std::min(at, text.size());
  const auto line =
      1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n');
  if (ended)
    return "truncated, or not the format its name says: OpenMesh's reader ran out of data at "
           "line " +
           std::to_string(line) + ", before the vertices and faces its header declares";
  std::istringstream rest(text.substr(at, 64));
  std::string word;
  rest >> word;
  if (is_non_finite_token(word))
    return "line " + std::to_string(line) + " holds a non-finite number '" + word + "'";
  return "malformed: OpenMesh's reader stopped at line " + std::to_string(line) +
         (word.empty() ? std::string() : " ('" + word + "')");
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

// The bytes of an OFF or PLY file as OpenMesh's reader is given them, a
// line end after the last line: reading past the end then means the file
// ended before what its header declares. An ASCII OFF file goes without its
// comments (from '#' to the end of a line), which that reader does not
// skip, so that commented files from other tools read; a binary one (its
// first line says BINARY) as it is.
std::string reader_text(const fs::path& path, bool off) {
  std::ifstream in(path, std::ios::binary);
  std::string out;
  if (!off || !std::getline(in, out) || out.find("BINARY") != std::string::npos) {
    in.clear();
    in.seekg(0);
    std::ostringstream all;
    all << in.rdbuf();
    return all.str() + '\n';
  }
  in.seekg(0);
  out.clear();
  for (std::string line; std::getline(in, line);) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    out += line;
    out += '\n';
  }
  return out;
}

// What OpenMesh makes of the file, with our checks of its answer: runs in
// the reading child (read_mesh). OpenMesh reads first, and nothing parses
// in front of it: OFF and PLY from a stream that stops its reader at once
// where it reads past the end (a file cut short, or counts larger than the
// file) or cannot take a word (nan, text where a count belongs; a good file
// never fails a read of these readers, which would otherwise go on over
// garbage counts until the time limit), and says where; the other formats
// by name. The counts and values are then checked on what it read.
TriMesh read_here(const fs::path& path, MeshReadReport& report) {
  const std::string ext = lower_extension(path);
  const bool streamed = ext == ".off" || ext == ".ply";
  const std::string text = streamed ? reader_text(path, ext == ".off") : std::string();
  std::istringstream stream(text);
  stream.exceptions(std::ios::eofbit | std::ios::failbit | std::ios::badbit);
  // Where the stream stopped, if it did: the problem with the file.
  const auto stream_problem = [&]() -> std::string {
    if (!streamed || !stream.fail()) return {};
    const bool ended = stream.eof();
    stream.exceptions(std::ios::goodbit);
    stream.clear();
    const std::streamoff at = stream.tellg();
    return stopped_at(text, at < 0 ? text.size() : static_cast<std::size_t>(at), ended);
  };
  PolyMesh pm;
  pm.request_vertex_normals();
  pm.request_vertex_status();
  OpenMesh::IO::Options opt = OpenMesh::IO::Options::Custom;
  opt += OpenMesh::IO::Options::VertexNormal;
  std::vector<std::string> messages;
  bool ok = false;
  std::string problem;
  {
    OmErrCapture capture;
    try {
      ok = streamed ? OpenMesh::IO::read_mesh(pm, stream, ext, opt)
                    : OpenMesh::IO::read_mesh(pm, path.string(), opt);
    } catch (const std::bad_alloc&) {
      problem = "malformed file (the reader ran out of memory on its counts)";
    } catch (const std::exception& e) {
      problem = std::string("malformed file: ") + e.what();
    }
    if (const std::string stopped = stream_problem(); !stopped.empty()) problem = stopped;
    messages = capture.lines();
  }
  if (!problem.empty()) fail(path, problem);
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
        const TriMesh mesh = read_here(path, report);
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
