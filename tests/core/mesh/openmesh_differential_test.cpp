// Our mesh reader against OpenMesh's own: every file that OpenMesh reads
// correctly (it says so, with faces and finite points) is accepted, with
// OpenMesh's points and faces. Nothing of ours parses in front of it
// (mesh_io.cpp), so nothing may refuse what it reads: checked over files
// OpenMesh's own writer makes in each format and option, and over the
// fuzzers' committed inputs (fuzz/corpus).

#include <gtest/gtest.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "helpers.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

namespace fs = std::filesystem;
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

// What OpenMesh itself reads from `path`: nullopt where it does not read
// it correctly (refused, no faces, a point that is not finite).
std::optional<PolyMesh> openmesh_reads(const fs::path& path) {
  PolyMesh pm;
  OpenMesh::IO::Options opt;
  if (!OpenMesh::IO::read_mesh(pm, path.string(), opt) || pm.n_faces() == 0) return std::nullopt;
  for (const auto v : pm.vertices())
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(pm.point(v)[k])) return std::nullopt;
  return pm;
}

std::size_t triangles_of(const PolyMesh& pm) {
  std::size_t n = 0;
  for (const auto f : pm.faces()) n += pm.valence(f) - 2;
  return n;
}

// `path`, which OpenMesh reads as `pm`, read by us alike.
void expect_read_alike(const fs::path& path, const PolyMesh& pm) {
  SCOPED_TRACE(path.filename().string());
  TriMesh ours;
  try {
    ours = read_mesh(path);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "refused a file OpenMesh reads: " << e.what();
    return;
  }
  ASSERT_EQ(ours.vertex_count(), pm.n_vertices());
  EXPECT_EQ(ours.triangle_count(), triangles_of(pm));  // none of these is degenerate
  for (std::size_t i = 0; i < ours.vertex_count(); ++i) {
    const auto p = pm.point(PolyMesh::VertexHandle(static_cast<int>(i)));
    for (int k = 0; k < 3; ++k) ASSERT_EQ(ours.positions[i][k], p[k]) << "vertex " << i;
  }
}

PolyMesh to_openmesh(const TriMesh& mesh) {
  PolyMesh pm;
  std::vector<PolyMesh::VertexHandle> v;
  for (const glm::vec3& p : mesh.positions) v.push_back(pm.add_vertex({p.x, p.y, p.z}));
  for (const Triangle& t : mesh.triangles) pm.add_face(v[t[0]], v[t[1]], v[t[2]]);
  return pm;
}

TEST(OpenMeshDifferential, EveryFileOpenMeshsWriterMakesIsRead) {
  test::TempDir dir;
  const std::vector<std::pair<const char*, TriMesh>> meshes = {
      {"torus", make_torus(1.0f, 0.3f, 24, 12)},
      {"sphere", make_sphere(1.0f, 10, 16)},
      {"square", make_square(1.0f, 5)},
  };
  struct Way {
    const char* ext;
    OpenMesh::IO::Options::Flag flags;
    const char* name;
  };
  using O = OpenMesh::IO::Options;
  const Way ways[] = {
      {".off", O::Default, "ascii"},
      {".off", O::Binary, "binary"},
      {".ply", O::Default, "ascii"},
      {".ply", O::Binary, "binary"},
      {".ply", static_cast<O::Flag>(O::Binary | O::MSB), "binary-msb"},
      {".stl", O::Default, "ascii"},
      {".stl", O::Binary, "binary"},
      {".obj", O::Default, "ascii"},
  };
  int read = 0;
  for (const auto& [name, mesh] : meshes) {
    PolyMesh pm = to_openmesh(mesh);
    for (const Way& w : ways) {
      const fs::path file = dir / (std::string(name) + "-" + w.name + w.ext);
      ASSERT_TRUE(OpenMesh::IO::write_mesh(pm, file.string(), OpenMesh::IO::Options(w.flags), 9))
          << file;
      const std::optional<PolyMesh> theirs = openmesh_reads(file);
      ASSERT_TRUE(theirs) << file << ": OpenMesh does not read what it wrote";
      expect_read_alike(file, *theirs);
      ++read;
    }
  }
  EXPECT_EQ(read, 24);
}

TEST(OpenMeshDifferential, EveryFuzzerInputOpenMeshReadsIsRead) {
  int read = 0, refused_by_both = 0;
  for (const char* fuzzer : {"off_fuzzer", "ply_fuzzer", "stl_fuzzer", "obj_fuzzer"}) {
    for (const auto& entry : fs::directory_iterator(fs::path(IBFVS_FUZZ_CORPUS_DIR) / fuzzer)) {
      if (const std::optional<PolyMesh> theirs = openmesh_reads(entry.path())) {
        expect_read_alike(entry.path(), *theirs);
        ++read;
      } else {
        // What OpenMesh does not read correctly is one line naming the file.
        try {
          static_cast<void>(read_mesh(entry.path()));
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find(entry.path().filename().string()),
                    std::string::npos);
          ++refused_by_both;
        }
      }
    }
  }
  EXPECT_GT(read, 8);
  std::printf("fuzzer inputs: %d read alike, %d refused by both\n", read, refused_by_both);
}

}  // namespace
}  // namespace ibfvs
