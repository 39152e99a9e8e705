// `ibfvs geometry` run as a user runs it.

#include <filesystem>
#include <utility>

#include <gtest/gtest.h>

#include "command_runner.h"
#include "ibfvs/core/mesh_io.h"
#include "ibfvs/core/procedural.h"
#include "ibfvs/core/subdivision.h"

namespace ibfvs {
namespace {

using GeometryCommand = test::CommandTest;

TEST_F(GeometryCommand, WritesCurvatureThatRenderReads) {
  write_ply(loop_subdivide(make_icosahedron(2.0f), 3), dir_ / "ball.ply", true);
  const test::Result r = run("geometry ball.ply --subdivide 1 -o out.ply");
  ASSERT_EQ(r.status, 0) << r.err;
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
  // a little more near the twelve vertices of valence 5.
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    EXPECT_GT(m.scalars.at("kmin")[i], 0.6f);
    EXPECT_LT(m.scalars.at("kmax")[i], 0.85f);
  }
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
  expect_error("geometry sq.off -o out.obj", "--out: must be a .ply file");
  expect_error("geometry sq.off -o nodir/out.ply", "--out: the folder 'nodir'");
  expect_error("geometry sq.off --subdivide 9", "--subdivide");
  file("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n");
  expect_error("geometry bad.off", "bad.off: truncated or malformed");
}

}  // namespace
}  // namespace ibfvs
