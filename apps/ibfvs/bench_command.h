#pragma once
// `ibfvs bench`: the paper's Table 1 protocol (frames per second of texture
// synthesis on the Loop-subdivided cow, three image sizes, static and
// rotating), printed beside the paper's figures.

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace ibfvs::app {

struct BenchOptions {
  std::string mesh;                     ///< empty: the fetched cow (data/meshes/cow.off)
  std::vector<int> subdivide{0, 1, 2};  ///< Loop levels: 5.8K, 23.2K, 92.8K triangles
  std::vector<std::string> sizes{"256x256", "512x512", "1024x1024"};
  double seconds = 2.0;   ///< at least this long per measurement
  int repeats = 3;        ///< measurements per cell; the median is reported
  int warmup = 20;        ///< frames before measuring
  float orbit = 1.0f;     ///< degrees per frame in the dynamic case
  std::string csv, json;  ///< also write the results there
  /// The looks measured, one table each: "paper" (style paper: Table 1's
  /// algorithm, whose cells the verdict counts) and "default" (the defaults).
  std::vector<std::string> looks{"paper", "default"};
  /// Scene settings KEY=VALUE on top of each look.
  std::vector<std::string> settings;
  bool quiet = false;
};

/// One measured cell.
struct BenchCell {
  std::string look;  ///< "paper" or "default"
  int subdivide = 0;
  std::size_t triangles = 0;
  int width = 0, height = 0;
  bool dynamic = false;
  double fps = 0.0;  ///< median over the repeats
  std::vector<double> runs;
};

void add_bench_options(CLI::App& command, BenchOptions& options);

/// The paper's Table 1 figure for a cell (GeForce4 Ti200, 2003), or 0 when
/// the paper has none (other meshes, levels or sizes).
double paper_table1_fps(int subdivide, int width, int height, bool dynamic);

/// Runs the protocol; prints the table; returns the exit status.
int run_bench(const BenchOptions& options);

}  // namespace ibfvs::app
