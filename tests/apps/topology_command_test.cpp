// `ibfvs topology` run as a user runs it: its summary, and its .vtp as
// VTK's own reader reads it (the contract of issue 64).

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "command_runner.h"
#include "helpers.h"
#include "ibfvs/core/image/image.h"

#ifdef IBFVS_HAVE_VTK
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>
#endif

namespace ibfvs {
namespace {

using TopologyCommand = test::CommandTest;

TEST_F(TopologyCommand, HeightOnATorusGivesTwoNodesTwoSaddlesAndTheFile) {
  const test::Result r = run("topology torus --field gradient:down:1,0,0.137 -o torus.vtp");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("torus: 4 critical points (2 saddles, 1 attracting node, 1 repelling "
                       "node)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("index sum 0 (Euler characteristic 0)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("wrote torus.vtp"), std::string::npos) << r.out;
#ifdef IBFVS_HAVE_VTK
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dir_ / "torus.vtp").c_str());
  reader->Update();
  vtkPolyData* out = reader->GetOutput();
  ASSERT_EQ(out->GetNumberOfVerts(), 4);
  vtkDataArray* kind = out->GetCellData()->GetArray("kind");
  vtkDataArray* index = out->GetPointData()->GetArray("index");
  vtkDataArray* eigen = out->GetPointData()->GetArray("eigenvalues");
  ASSERT_TRUE(kind && index && eigen && out->GetPointData()->GetArray("magnitude"));
  EXPECT_EQ(eigen->GetNumberOfComponents(), 4);
  std::multiset<int> kinds;
  int index_sum = 0;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c) {
    kinds.insert(static_cast<int>(kind->GetTuple1(c)));
    if (c < 4) {  // the vertices come first: each names its point
      const vtkIdType p = out->GetCell(c)->GetPointId(0);
      index_sum += static_cast<int>(index->GetTuple1(p));
      EXPECT_EQ(index->GetTuple1(p), kind->GetTuple1(c) == 1 ? -1 : 1);
    }
  }
  EXPECT_EQ(index_sum, 0);
  EXPECT_EQ(kinds.count(1), 2u);
  EXPECT_EQ(kinds.count(2), 1u);
  EXPECT_EQ(kinds.count(3), 1u);
  // Every other cell is a line of kind 10 or 11.
  EXPECT_EQ(kinds.count(10) + kinds.count(11) + 4,
            static_cast<std::size_t>(out->GetNumberOfCells()));
  EXPECT_EQ(out->GetNumberOfLines() + 4, out->GetNumberOfCells());
#endif
}

TEST_F(TopologyCommand, ATurningSphereHasTwoCentresAndNoLines) {
  const test::Result r = run("topology globe:4 --field rotate:0.3,0.2,0.93 -o globe.vtp");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("globe:4: 2 critical points (2 centres), 0 separation lines, 0 attachment "
                       "lines; index sum 2 (Euler characteristic 2)"),
            std::string::npos)
      << r.out;
}

// `render --overlay topology`: the same features over the picture, in the
// kinds' colours, with the legend's dark box in the bottom left corner.
TEST_F(TopologyCommand, RenderDrawsTheOverlay) {
  const test::Result drawn =
      run("render torus --field gradient:down:1,0.5,0.137 --overlay topology --size 240x200 "
          "--frames 20 --out over.png -q");
  ASSERT_EQ(drawn.status, 0) << drawn.err;
  const test::Result plain =
      run("render torus --field gradient:down:1,0.5,0.137 --size 240x200 --frames 20 "
          "--out plain.png -q");
  ASSERT_EQ(plain.status, 0) << plain.err;
  const ImageU8 over = read_png(dir_ / "over.png"), without = read_png(dir_ / "plain.png");
  EXPECT_GT(test::pixels_of_colour(over, 220, 20, 30), 30u);  // separation lines
  EXPECT_GT(test::pixels_of_colour(over, 30, 90, 255), 30u);  // attachment lines
  EXPECT_GT(test::pixels_of_colour(over, 255, 221, 0), 10u);  // saddles
  EXPECT_EQ(
      test::pixels_of_colour(without, 220, 20, 30) + test::pixels_of_colour(without, 255, 221, 0),
      0u);
  // The legend: the box's dark grey at its corner (rows are bottom-up).
  const std::uint8_t* corner = &over.pixels[(5u * over.width + 5u) * over.channels];
  EXPECT_LT(corner[0] + corner[1] + corner[2], 3 * 30);
}

TEST_F(TopologyCommand, BadRequestsAreOneLine) {
  const auto one_error = [&](const std::string& args, const std::string& says) {
    const test::Result r = run(args);
    EXPECT_EQ(r.status, 1) << args;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  };
  one_error("topology torus", "--out: give the .vtp file to write");
  one_error("topology torus -o t.png", "a .vtp file, got 't.png'");
  one_error("topology torus -o no/such/t.vtp", "the folder 'no/such' does not exist");
  one_error("topology torus --min-length -1 -o t.vtp", "--min-length");
  // A zero field: no features, and the summary says why.
  const test::Result zero = run("topology torus --field uniform:0,0,0 -o z.vtp");
  EXPECT_EQ(zero.status, 0) << zero.err;
  EXPECT_NE(zero.out.find("0 critical points, 0 separation lines, 0 attachment lines; index sum "
                          "0 (Euler characteristic 0); the field is zero on 20480 triangles"),
            std::string::npos)
      << zero.out;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "z.vtp"));
}

}  // namespace
}  // namespace ibfvs
