// `ibfvs geometry` run as a user runs it.

#include <algorithm>
#include <array>
#include <filesystem>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "command_runner.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/mesh/subdivision.h"

namespace ibfvs {
namespace {

using GeometryCommand = test::CommandTest;

TEST_F(GeometryCommand, WritesCurvatureThatRenderReads) {
  write_ply(loop_subdivide(make_icosahedron(2.0f), 3), dir_ / "ball.ply", true);
  const test::Result r = run("geometry ball.ply --subdivide 1 -o out.ply");
  ASSERT_EQ(r.status, 0) << r.err;
  // A subdivision surface is exact: the quartic, chosen and said so.
  EXPECT_NE(r.out.find("by the quartic jet (the mesh looks exact"), std::string::npos) << r.out;
  const test::Result cubic = run("geometry ball.ply --curvature-fit cubic");
  EXPECT_EQ(cubic.status, 0) << cubic.err;
  EXPECT_NE(cubic.out.find("by the cubic fit with normals."), std::string::npos) << cubic.out;
  EXPECT_NE(r.out.find("ball.ply: 2562 vertices, 5120 triangles after 1 Loop subdivisions; closed"),
            std::string::npos)
      << r.out;
  const std::string header = test::read_file(dir_ / "out.ply").substr(0, 800);
  for (const char* p : {"property float nx", "property float kmin", "property float kmax",
                        "property float dminx", "property float dmaxz", "binary_little_endian"})
    EXPECT_NE(header.find(p), std::string::npos) << p;
  const TriMesh m = read_mesh(dir_ / "out.ply");
  ASSERT_EQ(m.scalars.count("kmin"), 1u);
  // Loop shrinks an icosahedron of radius 2 to a convex near-sphere of radius
  // about 1.41 (see the subdivision test): curvature about 0.71 everywhere,
  // more on the 60 neighbours of the twelve vertices of valence 5 (0.92: the
  // control mesh bends more there).
  std::size_t above = 0;
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    EXPECT_GT(m.scalars.at("kmin")[i], 0.6f);
    EXPECT_LT(m.scalars.at("kmax")[i], 0.95f);
    above += m.scalars.at("kmax")[i] > 0.85f;
  }
  EXPECT_LE(above, 60u);
  const test::Result render = run("render --mesh out.ply --size 64x64 --frames 3 --out o.png -q");
  EXPECT_EQ(render.status, 0) << render.err;
  const test::Result ascii = run("geometry out.ply --ascii -o again.ply -q");
  ASSERT_EQ(ascii.status, 0) << ascii.err;
  EXPECT_NE(test::read_file(dir_ / "again.ply").find("format ascii"), std::string::npos);
  EXPECT_TRUE(ascii.out.empty());
}

TEST_F(GeometryCommand, TheCowOfTable1) {
  const std::string cow = std::string(IBFVS_TEST_DATA_DIR) + "/meshes/cow.off";
  if (!std::filesystem::exists(cow)) GTEST_SKIP() << "fetched data missing: " << cow;
  // The paper's Table 1 meshes: 5.8K, 23.2K and 92.8K triangles.
  for (const auto& [level, count] : {std::pair{0, "5804"}, {1, "23216"}, {2, "92864"}}) {
    const test::Result r = run("geometry '" + cow + "' --subdivide " + std::to_string(level));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find(std::string(count) + " triangles"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("closed"), std::string::npos) << r.out;
  }
  const test::Result r =
      run("render --mesh '" + cow + "' --subdivide 2 --size 64x64 --frames 2 --out c.png");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("92864 triangles"), std::string::npos) << r.out;
}

TEST_F(GeometryCommand, SummaryCountsBoundaries) {
  file("sq.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  const test::Result r = run("geometry sq.off");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("4 vertices, 2 triangles; 1 boundary loop."), std::string::npos) << r.out;
}

TEST_F(GeometryCommand, BadInputFailsCleanly) {
  expect_error("geometry", "mesh");
  expect_error("geometry missing.off", "missing.off: no such file");
  file("sq.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  expect_error("geometry sq.off -o out.obj", "--out: must be a .ply or .vtp file");
  expect_error("geometry sq.off -o nodir/out.ply", "--out: the folder 'nodir'");
  expect_error("geometry sq.off --subdivide 13", "--subdivide");
  ASSERT_EQ(run("geometry sq.off -o sq.ply").status, 0);
  expect_error("geometry sq.ply -o ./sq.ply", "--out: ./sq.ply is the input mesh");
  // Refused before subdividing, with what it would need (IBFVS_MEMORY_LIMIT
  // stands for a smaller machine).
  const test::Result r = run("geometry sq.off --subdivide 12", "IBFVS_MEMORY_LIMIT=1G");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--subdivide: sq.off subdivided 12 times (33.6 million triangles) would "
                       "need about 3.4 GiB of memory; this machine has 1.0 GiB; at most 11 "
                       "levels fit"),
            std::string::npos)
      << r.err;
  expect_error("geometry sq.off --curvature-fit best", "--curvature-fit: best not in");
  file("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n");
  expect_error("geometry bad.off",
               "bad.off: truncated or malformed: a face references a vertex index out of range");
  // OpenMesh looped forever on an OFF face of no vertices (until the
  // reader's time limit, IBFVS_READER_SECONDS); its stream now stops it at
  // once, where it stopped reading: one line naming the file and the line.
  file("hang.off", "OFF 0\n1 2 0\n0 1 00\n 0 777777777735\n3 0 203\n");
  const test::Result hang = run("geometry hang.off", "IBFVS_READER_SECONDS=2");
  EXPECT_EQ(hang.status, 1);
  EXPECT_EQ(hang.err.rfind("ibfvs: error: ", 0), 0u) << hang.err;
  EXPECT_NE(hang.err.find("hang.off: malformed: OpenMesh's reader stopped at line 4"),
            std::string::npos)
      << hang.err;
  EXPECT_EQ(hang.err.find('\n'), hang.err.size() - 1) << hang.err;
}

// A user's per-vertex data must still line up with the written vertices:
// the GPU's vertex-cache order is for rendering only. (The written file used
// to come out in cache order.)
TEST_F(GeometryCommand, WrittenVerticesKeepTheInputOrder) {
  // A sphere whose vertices are shuffled, so that any reordering shows.
  TriMesh ball = loop_subdivide(make_icosahedron(1.0f), 2);
  std::vector<std::uint32_t> perm(ball.vertex_count());
  for (std::size_t i = 0; i < perm.size(); ++i)
    perm[i] = static_cast<std::uint32_t>((i * 97) % perm.size());  // 97 is prime to 162
  TriMesh shuffled;
  shuffled.positions.resize(perm.size());
  for (std::size_t i = 0; i < perm.size(); ++i) shuffled.positions[perm[i]] = ball.positions[i];
  for (const Triangle& t : ball.triangles)
    shuffled.triangles.push_back({perm[t[0]], perm[t[1]], perm[t[2]]});
  write_ply(shuffled, dir_ / "in.ply", false);
  const test::Result r = run("geometry in.ply -o out.ply -q");
  ASSERT_EQ(r.status, 0) << r.err;
  const TriMesh in = read_mesh(dir_ / "in.ply");
  const TriMesh out = read_mesh(dir_ / "out.ply");
  ASSERT_EQ(out.vertex_count(), in.vertex_count());
  for (std::size_t i = 0; i < in.vertex_count(); ++i)
    ASSERT_EQ(out.positions[i], in.positions[i]) << "vertex " << i << " moved";
  ASSERT_EQ(out.triangles.size(), in.triangles.size());
  // The same triangles (each may start at another corner, none is lost).
  std::multiset<std::array<std::uint32_t, 3>> a, b;
  const auto canonical = [](Triangle t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return std::array<std::uint32_t, 3>{t[0], t[1], t[2]};
  };
  for (const Triangle& t : in.triangles) a.insert(canonical(t));
  for (const Triangle& t : out.triangles) b.insert(canonical(t));
  EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace ibfvs
