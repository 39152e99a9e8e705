// VTK and OpenFOAM data through the command, as a CFD user runs it: arrays by
// name, reversed wall shear stress, .vtp out of geometry and export, and one
// line with exit status 1 for every kind of bad file.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "apps/command_runner.h"
#include "ibfvs/core/image/image.h"

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

// A legacy binary file (big-endian) of a square (n x n cells over
// [-0.6, 0.6]^2) turned `degrees` about +Z, with a swirl v; `nan`: its
// point 5 is NaN (which VTK's reader reads as it is).
std::string turned_square(double degrees, int n = 6, bool nan = false) {
  const double a = degrees * 3.14159265358979 / 180.0;
  std::string points, polys, vectors;
  const auto put = [](std::string& out, std::uint32_t bits) {
    for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((bits >> shift) & 0xff);
  };
  const auto put_float = [&](std::string& out, float f) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &f, 4);
    put(out, bits);
  };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -0.6 + 1.2 * i / n, y = -0.6 + 1.2 * j / n;
      const double px = std::cos(a) * x - std::sin(a) * y, py = std::sin(a) * x + std::cos(a) * y;
      const bool bad = nan && j * (n + 1) + i == 5;
      put_float(points, bad ? std::nanf("") : static_cast<float>(px));
      put_float(points, static_cast<float>(py));
      put_float(points, 0.0f);
      put_float(vectors, static_cast<float>(-py));
      put_float(vectors, static_cast<float>(px));
      put_float(vectors, 0.0f);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t v = j * (n + 1) + i;
      for (const std::uint32_t x : {4u, v, v + 1, v + n + 2, v + n + 1}) put(polys, x);
    }
  const int count = (n + 1) * (n + 1);
  return "# vtk DataFile Version 3.0\nturned\nBINARY\nDATASET POLYDATA\nPOINTS " +
         std::to_string(count) + " float\n" + points + "\nPOLYGONS " + std::to_string(n * n) + " " +
         std::to_string(5 * n * n) + "\n" + polys + "\nPOINT_DATA " + std::to_string(count) +
         "\nVECTORS v float\n" + vectors + "\n";
}

// The surface pixels of a picture: those unlike its corner (the background).
std::vector<bool> surface_of(const std::filesystem::path& png) {
  const ImageU8 image = read_png(png);
  std::vector<bool> out(static_cast<std::size_t>(image.width) * image.height);
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < 3; ++c)
      out[i] = out[i] || image.pixels[i * image.channels + c] != image.pixels[c];
  return out;
}

// A .pvd of a square turning 20 degrees a step (the points move) is drawn at
// each step on that step's points, not the first step's; a step of other
// cells plays too; a step with a NaN point is one line naming it.
TEST_F(DatasetCommand, SeriesWhosePointsMovePlayOnEachStepsPoints) {
  std::string pvd = "<VTKFile type=\"Collection\"><Collection>\n";
  for (int k = 0; k < 3; ++k) {
    const std::string name = "t" + std::to_string(k) + ".vtk";
    file(name, turned_square(20.0 * k, k == 2 ? 9 : 6));
    pvd += "<DataSet timestep=\"" + std::to_string(k) + "\" file=\"" + name + "\"/>\n";
  }
  file("turn.pvd", pvd + "</Collection></VTKFile>\n");
  Result r =
      run("render turn.pvd --field file:v --frames-per-step 1 --frames 3 --size 64x64 --out "
          "f%04d.png -q");
  ASSERT_EQ(r.status, 0) << r.err;
  for (int k = 0; k < 3; ++k) {
    r = run("render turn.pvd --field file:v --time " + std::to_string(k) +
            " --frames 1 --size 64x64 --out s" + std::to_string(k) + ".png -q");
    ASSERT_EQ(r.status, 0) << r.err;
    char frame[32];
    std::snprintf(frame, sizeof frame, "f%04d.png", k);
    const std::vector<bool> played = surface_of(dir_ / frame);
    std::snprintf(frame, sizeof frame, "s%d.png", k);
    const std::vector<bool> alone = surface_of(dir_ / frame);
    std::size_t differ = 0, surface = 0;
    for (std::size_t i = 0; i < played.size(); ++i) {
      differ += played[i] != alone[i];
      surface += alone[i];
    }
    EXPECT_GT(surface, 500u);
    EXPECT_LT(differ, surface / 50) << "step " << k;  // the silhouette's pixels at most
  }
  file("t1.vtk", turned_square(20.0, 6, true));
  expect_error("render turn.pvd --field file:v --frames 3 --out x.png",
               "turn.pvd: step 1: the data: point 5 has a non-finite coordinate");
  expect_error("render turn.pvd --field file:v --time 1 --frames 3 --out x.png",
               "turn.pvd: step 1: the data: point 5 has a non-finite coordinate");
  // Step 1 without the array v (another mesh, another array).
  std::string other = kSquare;
  other.replace(other.find("VECTORS v"), 9, "VECTORS w");
  file("t1.vtk", other);
  expect_error("render turn.pvd --field file:v --frames 3 --out x.png",
               "turn.pvd: step 1: file:v: no such array");
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
#if defined(__SANITIZE_ADDRESS__) || \
    defined(IBFVS_ASAN_RUNTIME)  // the runtime, built with it or not
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
