// VTK and OpenFOAM data through the command, as a CFD user runs it: arrays by
// name, reversed wall shear stress, .vtp out of geometry and export, and one
// line with exit status 1 for every kind of bad file.

#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "apps/command_runner.h"

namespace ibfvs {
namespace {

using DatasetCommand = test::CommandTest;
using test::Result;

// A unit square of two triangles with point vectors v, a point scalar p and
// a cell vector wss (as FIELD data), legacy ASCII.
const char* kSquare = R"(# vtk DataFile Version 4.2
square
ASCII
DATASET POLYDATA
POINTS 4 float
0 0 0  1 0 0  1 1 0  0 1 0
POLYGONS 1 5
4 0 1 2 3
POINT_DATA 4
VECTORS v float
1 0 0  1 0 0  1 0 0  1 0 0
SCALARS p float 1
LOOKUP_TABLE default
1 2 3 4
CELL_DATA 1
FIELD FieldData 1
wss 3 1 float
0 -1 0
)";

#ifdef IBFVS_HAVE_VTK

TEST_F(DatasetCommand, RendersANamedArrayReversedColouredByAScalar) {
  file("square.vtk", kSquare);
  const Result r =
      run("render square.vtk --field file:wss --reverse --color-by p --frames 3 --size 64x64 "
          "--out a.png");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("field file:wss"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "a.png"));
}

TEST_F(DatasetCommand, GeometryAndExportWriteVtp) {
  file("square.vtk", kSquare);
  Result r = run("geometry square.vtk -q -o curv.vtp");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("render curv.vtp --field file:v --frames 2 --size 64x64 --out b.png --export model.vtp");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "model.vtp"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "model.png"));
  EXPECT_NE(test::read_file(dir_ / "model.vtp").find("TCoords"), std::string::npos);
  // The curvature arrays came through: kmin as a scalar, dmin as a vector.
  r = run("render curv.vtp --field file:dmin --color-by kmin --frames 2 --size 64x64 --out c.png");
  EXPECT_EQ(r.status, 0) << r.err;
}

// A .pvd of three legacy files whose vectors turn: played through, each step
// frames_per_step frames; a single step by --time; a range too long refused.
TEST_F(DatasetCommand, PvdSeriesPlaysThroughItsSteps) {
  std::string pvd = "<VTKFile type=\"Collection\"><Collection>\n";
  const std::string square = kSquare;
  const std::size_t vectors = square.find("VECTORS v float\n") + 16;
  const std::size_t after = square.find('\n', vectors);
  for (int k = 0; k < 3; ++k) {
    const std::string v = std::to_string(k) + " 1 0  ";
    const std::string step = square.substr(0, vectors) + v + v + v + v + square.substr(after);
    char name[32], entry[96];
    std::snprintf(name, sizeof name, "s%d.vtk", k);
    std::snprintf(entry, sizeof entry, "<DataSet timestep=\"%d\" file=\"%s\"/>\n", k, name);
    file(name, step);
    pvd += entry;
  }
  file("run.pvd", pvd + "</Collection></VTKFile>\n");
  Result r =
      run("render run.pvd --field file:v --frames-per-step 2 --frames 7 --size 64x64 "
          "--out a.png");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("render run.pvd --field file:v --time 2 --frames 2 --size 64x64 --out b.png");
  ASSERT_EQ(r.status, 0) << r.err;
  expect_error("render run.pvd --field file:v --time 1:3 --frames 2 --out c.png",
               "run.pvd: has 3 steps (0..2), asked for 1:3");
}

TEST_F(DatasetCommand, BadDataOneLineExitOne) {
  file("square.vtk", kSquare);
  expect_error("render square.vtk --field file:nope --frames 1 --out x.png",
               "square.vtk: file:nope: no such array (arrays: v (3), wss (3), p (1))");
  expect_error("render square.vtk --field file:p --frames 1 --out x.png",
               "file:p: the array has 1 component; a field needs 3");
  expect_error("render square.vtk --frames 1 --out x.png", "name one with file:NAME");
  expect_error("render square.vtk --blocks wing --frames 1 --out x.png",
               "square.vtk: has no blocks to choose from");
  file("garbage.vtp", "this is not XML");
  expect_error("render garbage.vtp --frames 1 --out x.png", "garbage.vtp: ");
  file("huge.vtk",
       "# vtk DataFile Version 4.2\nx\nASCII\nDATASET POLYDATA\nPOINTS "
       "900000000000 float\n0 0 0\n");
  // VTK aborts on the allocation, in the child process that reads it
  // (under AddressSanitizer the sanitizer ends the child first).
#ifdef __SANITIZE_ADDRESS__
  expect_error("render huge.vtk --frames 1 --out x.png",
               "huge.vtk: VTK's reader stopped on it without an answer (exit status 1");
#else
  expect_error("render huge.vtk --frames 1 --out x.png",
               "huge.vtk: VTK's reader crashed on it (SIGABRT) after reporting: Unable to "
               "allocate 2700000000003 elements");
#endif
  expect_error("render square.vtk --field sample:nowhere.vtu:U:0.1 --frames 1 --out x.png",
               "nowhere.vtu: no such file");
  expect_error("geometry square.vtk -o out.vtx", "must be a .ply or .vtp file");
}

#else

TEST_F(DatasetCommand, WithoutVtkTheBuildSaysSo) {
  file("square.vtk", kSquare);
  expect_error("render square.vtk --frames 1 --out x.png",
               "VTK and OpenFOAM files need ibfvs built with ParaView's VTK");
}

#endif

}  // namespace
}  // namespace ibfvs
