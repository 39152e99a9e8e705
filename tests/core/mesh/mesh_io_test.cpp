#include <cmath>
#include <cstdlib>
#include <cstring>

#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <glm/geometric.hpp>

#include "helpers.h"
#include "ibfvs/core/image/image.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

using test::TempDir;
using test::write_file;

const char* kTetraOff =
    "OFF\n# a tetrahedron\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

// Expects read_mesh(path) to throw InputError whose message names the file
// and contains `problem`.
void expect_read_error(const std::filesystem::path& path, const std::string& problem) {
  try {
    read_mesh(path);
    FAIL() << "no error for " << path;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(problem), std::string::npos) << "expected '" << problem << "' in: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(MeshIo, ReadsOffWithComputedOutwardNormals) {
  TempDir dir;
  MeshReadReport report;
  const TriMesh m = read_mesh(write_file(dir / "tetra.off", kTetraOff), &report);
  EXPECT_EQ(m.vertex_count(), 4u);
  EXPECT_EQ(m.triangle_count(), 4u);
  EXPECT_FALSE(report.normals_from_file);
  ASSERT_EQ(m.normals.size(), 4u);
  const glm::vec3 centre(0.25f);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-5f);
    if (i > 0) {
      EXPECT_GT(glm::dot(m.normals[i], m.positions[i] - centre), 0.0f) << i;
    }
  }
}

TEST(MeshIo, TriangulatesObjPolygons) {
  TempDir dir;
  MeshReadReport report;
  const TriMesh m = read_mesh(
      write_file(dir / "quad.obj",
                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4\nf 2 5 6 3\n"),
      &report);
  EXPECT_EQ(m.triangle_count(), 4u);
  EXPECT_EQ(report.polygons_triangulated, 2u);
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(n.z, 1.0f, 1e-5f);
}

TEST(MeshIo, MergesDuplicateStlVertices) {
  TempDir dir;
  const std::string ascii =
      "solid two\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 "
      "0\nendloop\nendfacet\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 "
      "0\nendloop\nendfacet\n"
      "endsolid two\n";
  const TriMesh a = read_mesh(write_file(dir / "two.stl", ascii));
  EXPECT_EQ(a.vertex_count(), 4u);
  EXPECT_EQ(a.triangle_count(), 2u);

  // The same two triangles as binary STL.
  std::string bin(80, '\0');
  const std::uint32_t n = 2;
  bin.append(reinterpret_cast<const char*>(&n), 4);
  const float tris[2][12] = {{0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 1, 0},
                             {0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 1, 0}};
  for (const auto& t : tris) {
    bin.append(reinterpret_cast<const char*>(t), sizeof t);
    bin.append(2, '\0');
  }
  const TriMesh b = read_mesh(write_file(dir / "two_bin.stl", bin));
  EXPECT_EQ(b.vertex_count(), 4u);
  EXPECT_EQ(b.triangle_count(), 2u);

  // Cut short: OpenMesh takes it for ASCII STL, which has no facets.
  write_file(dir / "cut.stl", bin.substr(0, bin.size() - 7));
  expect_read_error(dir / "cut.stl", "no faces could be read");
}

TEST(MeshIo, PlyVectorsAndScalarsAsciiAndBinary) {
  TempDir dir;
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\n"
      "property float vx\nproperty float vy\nproperty float vz\nproperty float pressure\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 1 0 0 0.5\n1 0 0 0 1 0 1.5\n0 1 0 0 0 1 2.5\n3 0 1 2\n";
  const TriMesh m = read_mesh(write_file(dir / "f.ply", ply));
  ASSERT_EQ(m.vectors.size(), 3u);
  EXPECT_EQ(m.vectors[1], glm::vec3(0, 1, 0));
  ASSERT_EQ(m.scalars.count("pressure"), 1u);
  EXPECT_FLOAT_EQ(m.scalars.at("pressure")[2], 2.5f);
  EXPECT_EQ(m.scalars.count("vx"), 0u);

  // Round trip through our binary and ASCII writers.
  for (const bool binary : {true, false}) {
    const auto path = dir / (binary ? "bin.ply" : "ascii.ply");
    write_ply(m, path, binary);
    const TriMesh r = read_mesh(path);
    ASSERT_EQ(r.vertex_count(), 3u);
    ASSERT_EQ(r.vectors.size(), 3u);
    EXPECT_EQ(r.vectors[2], glm::vec3(0, 0, 1));
    EXPECT_FLOAT_EQ(r.scalars.at("pressure")[1], 1.5f);
    EXPECT_EQ(r.positions[1], glm::vec3(1, 0, 0));
  }
}

TEST(MeshIo, DropsDegenerateTrianglesAndCountsUnreferencedVertices) {
  TempDir dir;
  MeshReadReport report;
  const TriMesh m = read_mesh(write_file(dir / "d.off",
                                         "OFF\n6 3 0\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n5 5 5\n6 6 6\n"
                                         "3 0 1 2\n3 0 1 3\n3 0 2 1\n"),
                              &report);
  // 0 1 3 is collinear (zero area): dropped, which leaves vertex 3 unused
  // beside 4 and 5. 0 2 1 repeats 0 1 2 reversed: non-manifold, but kept on
  // the same vertices (a two-sided sheet), with no duplicated vertex.
  EXPECT_EQ(m.vertex_count(), 6u);
  EXPECT_EQ(m.triangle_count(), 2u);
  EXPECT_EQ(report.degenerate_removed, 1u);
  EXPECT_EQ(report.unreferenced_vertices, 3u);
  EXPECT_FALSE(report.warnings.empty());
  const Bounds b = mesh_bounds(m);
  EXPECT_EQ(b.max, glm::vec3(1, 1, 0));  // unused vertices do not widen the box
}

TEST(MeshIo, RejectsMissingEmptyAndUnknownFiles) {
  TempDir dir;
  expect_read_error(dir / "nope.off", "no such file");
  expect_read_error(dir.path(), "not a regular file");
  expect_read_error(write_file(dir / "empty.off", ""), "empty");
  expect_read_error(write_file(dir / "mesh.xyz", "1 2 3\n"), "unknown mesh format");
}

TEST(MeshIo, RejectsMalformedOff) {
  TempDir dir;
  expect_read_error(write_file(dir / "trunc.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n"),
                    "truncated");
  // What OpenMesh's reader made of each, from its own state (nothing of
  // ours parses in front of it): where it stopped, and why.
  expect_read_error(write_file(dir / "count.off", "OFF\nfour 4 0\n0 0 0\n"),
                    "stopped at line 2 ('four')");
  // A count no file of this size holds: OpenMesh's reservation fails in the
  // reading child (bad_alloc; under AddressSanitizer the child ends).
  expect_read_error(write_file(dir / "huge.off", "OFF\n999999999 1 0\n0 0 0\n"), "out of memory");
  expect_read_error(write_file(dir / "index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
                    "out of range");
  expect_read_error(write_file(dir / "nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"),
                    "non-finite");
  expect_read_error(write_file(dir / "inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 -inf 0\n3 0 1 2\n"),
                    "non-finite");
  expect_read_error(write_file(dir / "text.off", "hello, this is not a mesh\n"),
                    "not the format its name says");
  expect_read_error(write_file(dir / "nofaces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"),
                    "no faces");
}

TEST(MeshIo, RejectsMalformedPlyObjAndBinaryJunk) {
  TempDir dir;
  expect_read_error(write_file(dir / "png.ply", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)),
                    "Unable to parse header");
  expect_read_error(write_file(dir / "noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"),
                    "ran out of data at line");
  // A binary PLY cut short in its vertex data.
  TriMesh sq = make_square(1.0f, 4);
  write_ply(sq, dir / "full.ply", true);
  const std::string full = test::read_file(dir / "full.ply");
  write_file(dir / "cut.ply", full.substr(0, full.size() / 2));
  expect_read_error(dir / "cut.ply", "");
  expect_read_error(write_file(dir / "points.obj", "v 0 0 0\nv 1 0 0\n"), "no faces");
  expect_read_error(write_file(dir / "idx.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), "");
}

// Sets IBFVS_READER_SECONDS for one test.
class ReaderSeconds {
 public:
  explicit ReaderSeconds(const char* seconds) { ::setenv("IBFVS_READER_SECONDS", seconds, 1); }
  ~ReaderSeconds() { ::unsetenv("IBFVS_READER_SECONDS"); }
  ReaderSeconds(const ReaderSeconds&) = delete;
  ReaderSeconds& operator=(const ReaderSeconds&) = delete;
};

// Inputs the fuzzers found (fuzz/, docs/reliability.md). OpenMesh's readers
// looped forever, printed errors forever, reserved gigabytes or read out of
// bounds on them; they now read in a child process (support/isolation.h),
// with nothing of ours parsing in front: each is one line naming the file,
// within the reader's time limit (here 3 s), or a mesh that OpenMesh read.
// The two loops now end at once: the OFF and PLY readers' stream stops them
// at the first read that fails (mesh_io.cpp).
TEST(MeshIo, FuzzerFindingsEndCleanly) {
  TempDir dir;
  const ReaderSeconds quick("3");
  // An OFF face of no vertices (OpenMesh's ASCII OFF reader never returned).
  expect_read_error(
      write_file(dir / "hang.off", "OFF 0\n1 2 0\n0 1 00\n 0 777777777735\n3 0 203\n"),
      "OpenMesh's reader stopped at line 4 ('3')");
  expect_read_error(write_file(dir / "empty-face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n0\n"),
                    "no faces could be read");
  // A PLY format line with junk in its version (OpenMesh printed errors forever).
  expect_read_error(write_file(dir / "format.ply",
                               "ply\nformat ascii HHHH1.0\nelement vertex 1\nproperty float x\n"
                               "property float y\nproperty float z\nend_header\n0 0 0\n"),
                    "OpenMesh's reader stopped at line 2 ('HHHH1.0')");
  expect_read_error(write_file(dir / "keyword.ply",
                               "ply\nformat ascii 1.0\nelement vertex 1\npropemat ascii 1.0\n"
                               "end_header\n0 0 0\n"),
                    "cannot parse the mesh");
  // A keyword inside an obj_info line (OpenMesh's word-by-word header reader
  // took it for an element and reserved gigabytes), and an element whose
  // count no file of this size could hold.
  expect_read_error(write_file(dir / "info.ply",
                               "ply\nformat ascii 1.0\nelement vertex 1\nobj_info x element face "
                               "4\nproperty float x\nproperty float y\nproperty float z\n"
                               "end_header\n0 0 0\n"),
                    "cannot parse the mesh");
  expect_read_error(write_file(dir / "count.ply",
                               "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                               "property float y\nproperty float z\nelement junk 99999999\n"
                               "end_header\n0 0 0\n"),
                    "");
  // A negative value of an unsigned colour (OpenMesh's ASCII reader stopped
  // at the sign and, in the fuzzer's input, grew a list of faces until
  // memory ran out): here it reads.
  EXPECT_EQ(read_mesh(write_file(dir / "sign.ply",
                                 "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                 "property float y\nproperty float z\nproperty uchar red\n"
                                 "element face 1\nproperty list uchar int vertex_indices\n"
                                 "end_header\n0 0 0 255\n1 0 0 0\n0 1 0 -1\n3 0 1 2\n"))
                .triangle_count(),
            1u);
  // An OBJ face naming a normal given after it (OpenMesh read past its
  // array), a number out of range, a face naming a vertex given after it.
  expect_read_error(
      write_file(dir / "normal.obj", "v 1 0 0\nv 1 0 0\nv 0 1 0\nf -3//1 -2//1 -1//1\nvn 0 0 1\n"),
      "");
  expect_read_error(write_file(dir / "big.obj", "v 1e380 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "");
  EXPECT_EQ(read_mesh(write_file(dir / "ahead.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n"))
                .triangle_count(),
            1u);
}

// Binary files with a face out of range, cut short or too small: OpenMesh's
// own answers, each one line naming the file.
TEST(MeshIo, BrokenBinaryPlyAndOffAreCleanErrors) {
  TempDir dir;
  const auto ply = [&](const char* name, std::uint8_t count, std::int32_t index, bool cut) {
    std::string bytes =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    bytes.append(reinterpret_cast<const char*>(p), sizeof p);
    bytes.push_back(static_cast<char>(count));
    const std::int32_t ids[3] = {0, 1, index};
    bytes.append(reinterpret_cast<const char*>(ids), cut ? 8 : sizeof ids);
    return write_file(dir / name, bytes);
  };
  EXPECT_EQ(read_mesh(ply("good.ply", 3, 2, false)).triangle_count(), 1u);
  expect_read_error(ply("index.ply", 3, 7, false), "no faces could be read");
  expect_read_error(ply("short.ply", 3, 2, true), "truncated");
  expect_read_error(ply("two.ply", 2, 2, false), "no faces could be read");
  // Binary OFF: big-endian counts, coordinates, faces.
  const auto be = [](std::uint32_t v) {
    const char b[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 8), static_cast<char>(v)};
    return std::string(b, 4);
  };
  std::string off = "OFF BINARY\n" + be(3) + be(1) + be(0);
  for (int k = 0; k < 9; ++k) off += be(0);
  expect_read_error(write_file(dir / "bin.off", off + be(3) + be(0) + be(1) + be(9) + be(0)), "");
  expect_read_error(write_file(dir / "cut.off", off + be(3) + be(0)), "");
}

TEST(MeshIo, BinaryPlyWithNonFiniteCoordinateIsRejected) {
  TempDir dir;
  TriMesh sq = make_square(1.0f, 2);
  sq.positions[3].y = std::nanf("");
  write_ply(sq, dir / "nan.ply", true);
  expect_read_error(dir / "nan.ply", "non-finite");
}

TEST(MeshIo, NonFiniteVectorsAreReadAsIs) {
  // The reader keeps what the file says; evaluate_field zeroes and reports.
  TempDir dir;
  TriMesh sq = make_square(1.0f, 2);
  sq.vectors.assign(sq.vertex_count(), glm::vec3(1, 0, 0));
  sq.vectors[4] = glm::vec3(std::nanf(""), 0, 0);
  write_ply(sq, dir / "v.ply", true);
  const TriMesh m = read_mesh(dir / "v.ply");
  ASSERT_EQ(m.vectors.size(), sq.vertex_count());
  EXPECT_TRUE(std::isnan(m.vectors[4].x));
}

// A square with texture coordinates u = x, v = y (mapped to [0,1]) and a
// 4x2 texture whose bottom row is red and top row blue.
struct TexturedSquare {
  TriMesh mesh = make_square(1.0f, 3);
  std::vector<glm::vec2> uv;
  std::filesystem::path png;
  explicit TexturedSquare(const std::filesystem::path& dir) : png(dir / "tex.png") {
    for (const glm::vec3& p : mesh.positions) uv.emplace_back((p.x + 1) / 2, (p.y + 1) / 2);
    ImageU8 image(4, 2, 3);
    for (int x = 0; x < 4; ++x) {
      image.pixels[static_cast<std::size_t>(x) * 3] = 255;          // row 0 (bottom): red
      image.pixels[static_cast<std::size_t>(4 + x) * 3 + 2] = 255;  // row 1 (top): blue
    }
    write_png(image, png);
  }
};

TEST(MeshIo, TexturedObjReadsBackWithItsCoordinates) {
  TempDir dir;
  const TexturedSquare sq(dir.path());
  write_obj_textured(sq.mesh, sq.uv, dir / "sq.obj", "tex.png");
  const TriMesh back = read_mesh(dir / "sq.obj");
  EXPECT_EQ(back.vertex_count(), sq.mesh.vertex_count());
  EXPECT_EQ(back.triangle_count(), sq.mesh.triangle_count());
  EXPECT_NE(test::read_file(dir / "sq.mtl").find("map_Kd tex.png"), std::string::npos);
  EXPECT_THROW(write_obj_textured(sq.mesh, {}, dir / "x.obj", "tex.png"), InputError);
}

// Reads a glTF or GLB back through tinygltf and checks it against the square.
void expect_gltf_round_trip(const std::filesystem::path& file, const TexturedSquare& sq) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = file.extension() == ".glb"
                      ? loader.LoadBinaryFromFile(&model, &err, &warn, file.string())
                      : loader.LoadASCIIFromFile(&model, &err, &warn, file.string());
  ASSERT_TRUE(ok) << err;
  EXPECT_TRUE(err.empty()) << err;
  EXPECT_TRUE(warn.empty()) << warn;
  ASSERT_EQ(model.meshes.size(), 1u);
  const tinygltf::Primitive& prim = model.meshes[0].primitives.at(0);
  auto data = [&](int accessor) {
    const tinygltf::Accessor& a = model.accessors.at(static_cast<std::size_t>(accessor));
    const tinygltf::BufferView& v = model.bufferViews.at(static_cast<std::size_t>(a.bufferView));
    return model.buffers.at(static_cast<std::size_t>(v.buffer)).data.data() + v.byteOffset +
           a.byteOffset;
  };
  const tinygltf::Accessor& pos =
      model.accessors.at(static_cast<std::size_t>(prim.attributes.at("POSITION")));
  const tinygltf::Accessor& tex =
      model.accessors.at(static_cast<std::size_t>(prim.attributes.at("TEXCOORD_0")));
  ASSERT_EQ(pos.count, sq.mesh.vertex_count());
  ASSERT_EQ(tex.count, sq.mesh.vertex_count());
  EXPECT_EQ(model.accessors.at(static_cast<std::size_t>(prim.indices)).count,
            sq.mesh.triangle_count() * 3);
  EXPECT_TRUE(prim.attributes.count("NORMAL"));
  std::vector<glm::vec3> p(pos.count);
  std::vector<glm::vec2> t(tex.count);
  std::memcpy(p.data(), data(prim.attributes.at("POSITION")), p.size() * sizeof(glm::vec3));
  std::memcpy(t.data(), data(prim.attributes.at("TEXCOORD_0")), t.size() * sizeof(glm::vec2));
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p[i], sq.mesh.positions[i]);
    // glTF puts v = 0 at the top of the image: the flip keeps the picture upright.
    EXPECT_FLOAT_EQ(t[i].x, sq.uv[i].x);
    EXPECT_FLOAT_EQ(t[i].y, 1.0f - sq.uv[i].y);
  }
  // The texture: tinygltf decodes it (a file beside the .gltf, or inside the .glb).
  ASSERT_EQ(model.images.size(), 1u);
  const tinygltf::Image& image = model.images[0];
  ASSERT_EQ(image.width, 4);
  ASSERT_EQ(image.height, 2);
  // glTF rows are top-down: the first row is the blue one.
  EXPECT_EQ(image.image.at(2), 255);
  EXPECT_EQ(image.image.at(0), 0);
  EXPECT_EQ(model.materials.at(0).pbrMetallicRoughness.baseColorTexture.index, 0);
}

TEST(MeshIo, TexturedGltfAndGlbReadBackThroughTinygltf) {
  TempDir dir;
  const TexturedSquare sq(dir.path());
  write_gltf_textured(sq.mesh, sq.uv, dir / "sq.gltf", sq.png);
  EXPECT_TRUE(std::filesystem::exists(dir / "sq.bin"));
  expect_gltf_round_trip(dir / "sq.gltf", sq);
  write_gltf_textured(sq.mesh, sq.uv, dir / "sq.glb", sq.png);
  expect_gltf_round_trip(dir / "sq.glb", sq);
  EXPECT_THROW(write_gltf_textured(sq.mesh, sq.uv, dir / "sq.fbx", sq.png), InputError);
  EXPECT_THROW(write_gltf_textured(sq.mesh, sq.uv, dir / "sq.glb", dir / "none.png"), InputError);
  EXPECT_THROW(write_gltf_textured(sq.mesh, {}, dir / "sq.glb", sq.png), InputError);
}

}  // namespace
}  // namespace ibfvs
