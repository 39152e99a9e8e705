// `ibfvs bench`: a tiny run of the Table 1 protocol prints a well-formed table
// (no assertion on time: benchmarks measure, tests do not).

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "command_runner.h"
#include "helpers.h"
#include "ibfvs/bench_command.h"

namespace ibfvs {
namespace {

using BenchCommand = test::CommandTest;
using test::Result;

TEST(BenchTable, PaperFiguresOfTable1) {
  EXPECT_EQ(app::paper_table1_fps(0, 256, 256, false), 600.0);
  EXPECT_EQ(app::paper_table1_fps(2, 1024, 1024, false), 40.0);
  EXPECT_EQ(app::paper_table1_fps(1, 512, 512, true), 22.7);
  EXPECT_EQ(app::paper_table1_fps(3, 512, 512, false), 0.0);  // not in the paper
  EXPECT_EQ(app::paper_table1_fps(0, 640, 480, false), 0.0);
}

TEST_F(BenchCommand, TinyRunPrintsTheTableAndFiles) {
  file("sq.off", "OFF\n4 2 0\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n3 0 1 2\n3 0 2 3\n");
  const Result r =
      run("bench --mesh sq.off --subdivide 0 1 --sizes 32x32 48x48 --seconds 0.02 --repeats 2 "
          "--warmup 2 --csv b.csv --json b.json --looks paper default");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("renderer: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| image | 2 triangles | 8 triangles |"), std::string::npos) << r.out;
  // A table per look, the paper's first.
  EXPECT_LT(r.out.find("The paper's look"), r.out.find("The default look")) << r.out;
  // A row per size, a cell per level: "static (dynamic)" figures.
  for (const char* row : {"| 32x32 | ", "| 48x48 | "}) {
    const std::size_t at = r.out.rfind(row);
    ASSERT_NE(at, std::string::npos) << r.out;
    const std::string line = r.out.substr(at, r.out.find('\n', at) - at);
    EXPECT_EQ(std::count(line.begin(), line.end(), '|'), 4) << line;
    EXPECT_EQ(std::count(line.begin(), line.end(), '('), 2) << line;
  }
  const std::string csv = test::read_file(dir_ / "b.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 2 * 2 * 2) << csv;  // header + cells
  EXPECT_NE(csv.find("\npaper,2,0,32,32,static,"), std::string::npos) << csv;
  const std::string json = test::read_file(dir_ / "b.json");
  EXPECT_NE(json.find("\"cells\": ["), std::string::npos) << json;
  EXPECT_EQ(std::count(json.begin(), json.end(), '{'), 1 + 16) << json;
}

TEST_F(BenchCommand, BadOptionsFailCleanly) {
  file("sq.off", "OFF\n4 2 0\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n3 0 1 2\n3 0 2 3\n");
  const std::string b = "bench --mesh sq.off ";
  expect_error(b + "--sizes 32", "--sizes: expected WxH");
  expect_error(b + "--subdivide 9", "--subdivide");
  expect_error(b + "--seconds 0", "--seconds");
  expect_error(b + "--repeats 0", "--repeats");
  expect_error("bench --mesh missing.off --seconds 0.01", "missing.off");
  expect_error(b + "--set filter", "--set: expected KEY=VALUE, got 'filter'");
  expect_error(b + "--set filter=99", "--filter: must be between 0 and 32 pixels");
  expect_error(b + "--set nonsense=1", "nonsense");
  expect_error(b + "--looks fancy", "--looks");
}

TEST_F(BenchCommand, SettingsChangeTheLook) {
  // The paper's look on the protocol: it runs, and the settings reach the scene.
  const test::Result r =
      run("bench --subdivide 0 --sizes 32x32 --seconds 0.02 --repeats 1 --warmup 1 -q "
          "--looks default --set profile=square --set scale=4 --set vg=0.02 --set filter=0 "
          "--set contrast=0");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("| 32x32 |"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("The paper's look"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace ibfvs
