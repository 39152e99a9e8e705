#include "ibfvs/bench_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <CLI/CLI.hpp>

#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/geometry/displacement.h"
#include "ibfvs/core/scene/camera.h"
#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/data_paths.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/gl/context.h"
#include "ibfvs/render/session.h"

namespace ibfvs::app {
namespace {

// "WxH" -> (W, H), 16..16384 each.
std::pair<int, int> parse_bench_size(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || x != 'x' || (in >> extra) || w < 16 || h < 16 || w > 16384 ||
      h > 16384)
    throw InputError("--sizes: expected WxH with 16..16384 pixels each, got '" + text + "'");
  return {w, h};
}

std::string cpu_name() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  return "unknown CPU";
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string fmt(double v) {
  char s[32];
  std::snprintf(s, sizeof s, v >= 100 ? "%.0f" : v >= 10 ? "%.1f" : "%.2f", v);
  return s;
}

std::string triangles_label(std::size_t n) {
  char s[32];
  if (n < 1000)
    std::snprintf(s, sizeof s, "%zu", n);
  else if (n >= 1000000)
    std::snprintf(s, sizeof s, "%.1fM", static_cast<double>(n) / 1e6);
  else
    std::snprintf(s, sizeof s, "%.1fK", static_cast<double>(n) / 1e3);
  return s;
}

}  // namespace

double paper_table1_fps(int subdivide, int width, int height, bool dynamic) {
  // Table 1 of the paper: fps on a GeForce4 Ti200; the dynamic case (a
  // rotating object) is the same for every image size.
  static const std::map<std::pair<int, int>, double> still = {
      {{0, 256}, 600.0}, {{1, 256}, 228.0}, {{2, 256}, 64.0},  {{0, 512}, 290.0}, {{1, 512}, 165.0},
      {{2, 512}, 58.8},  {{0, 1024}, 88.0}, {{1, 1024}, 72.4}, {{2, 1024}, 40.0}};
  static const double rotating[] = {76.9, 22.7, 6.6};
  if (width != height || subdivide < 0 || subdivide > 2) return 0.0;
  const auto it = still.find({subdivide, width});
  if (it == still.end()) return 0.0;
  return dynamic ? rotating[subdivide] : it->second;
}

void add_bench_options(CLI::App& cmd, BenchOptions& o) {
  cmd.add_option("--mesh", o.mesh,
                 "Mesh to measure. Default: the paper's cow, data/meshes/cow.off");
  cmd.add_option("--subdivide", o.subdivide, "Loop subdivision levels, one row each")
      ->capture_default_str();
  cmd.add_option("--sizes", o.sizes, "Image sizes WxH, one column each")->capture_default_str();
  cmd.add_option("--seconds", o.seconds, "Least time per measurement")->capture_default_str();
  cmd.add_option("--repeats", o.repeats, "Measurements per cell; the median is reported")
      ->capture_default_str();
  cmd.add_option("--warmup", o.warmup, "Frames rendered before measuring")->capture_default_str();
  cmd.add_option("--orbit", o.orbit, "Degrees per frame the object turns in the dynamic case")
      ->capture_default_str();
  cmd.add_option("--csv", o.csv, "Also write the results as CSV to this file");
  cmd.add_option("--json", o.json, "Also write the results as JSON to this file");
  cmd.add_option("--looks", o.looks,
                 "Looks to measure, a table each: paper (style paper, Table 1's algorithm: "
                 "the verdict counts its cells) and default (the default look)")
      ->check(CLI::IsMember({"paper", "default"}))
      ->capture_default_str();
  cmd.add_option("--set", o.settings,
                 "KEY=VALUE: a scene setting on top of each look (repeatable; ibfvs keys "
                 "lists them), e.g. --set filter=0 --set contrast=0");
  cmd.add_flag("-q,--quiet", o.quiet, "Print only the table");
}

namespace {

void apply_bench_settings(Scene& scene, const std::vector<std::string>& settings) {
  for (const std::string& setting : settings) {
    const std::size_t eq = setting.find('=');
    if (eq == std::string::npos)
      throw InputError("--set: expected KEY=VALUE, got '" + setting + "'");
    apply_setting(scene, setting.substr(0, eq), setting.substr(eq + 1));
  }
}

}  // namespace

int run_bench(const BenchOptions& o) {
  {  // bad settings fail before anything is printed
    Scene check;
    apply_bench_settings(check, o.settings);
  }
  if (o.subdivide.empty() || o.sizes.empty())
    throw InputError("--subdivide and --sizes need at least one value each");
  for (const int s : o.subdivide)
    if (s < 0 || s > 8) throw InputError("--subdivide: levels must be between 0 and 8");
  if (!(o.seconds > 0.0) || o.seconds > 3600.0) throw InputError("--seconds: must be in (0, 3600]");
  if (o.repeats < 1 || o.repeats > 100) throw InputError("--repeats: must be in 1..100");
  if (o.warmup < 0 || o.warmup > 100000) throw InputError("--warmup: must be in 0..100000");
  if (!std::isfinite(o.orbit) || std::abs(o.orbit) > 360.0f)
    throw InputError("--orbit: must be within -360..360 degrees per frame");
  std::vector<std::pair<int, int>> sizes;
  for (const std::string& s : o.sizes) sizes.push_back(parse_bench_size(s));
  std::string mesh_path = o.mesh;
  if (mesh_path.empty()) {
    const auto cow = find_data_file("meshes/cow.off");
    if (!cow)
      throw InputError("the cow of Table 1 is missing (" + (data_dir() / "meshes").string() +
                       "); run scripts/fetch_data.sh or give --mesh");
    mesh_path = cow->string();
  }
  for (const std::string& path : {o.csv, o.json})
    if (!path.empty()) {
      std::ofstream probe(path, std::ios::app);
      if (!probe) throw InputError(path + ": cannot open for writing");
    }

  gl::HeadlessContext context;
  std::string renderer_name = context.renderer();
  const char* lp_threads = std::getenv("LP_NUM_THREADS");
  if (lp_threads != nullptr && renderer_name.find("llvmpipe") != std::string::npos)
    renderer_name += ", LP_NUM_THREADS=" + std::string(lp_threads);
  const std::string cpu =
      cpu_name() + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
  if (!o.quiet)
    std::printf(
        "ibfvs bench: %s\n  renderer: %s\n  CPU: %s\n  %.1f s per measurement, median "
        "of %d, %d warm-up frames, dynamic: %.1f degrees per frame, glFinish every "
        "frame\n",
        mesh_path.c_str(), renderer_name.c_str(), cpu.c_str(), o.seconds, o.repeats, o.warmup,
        o.orbit);
  std::fflush(stdout);  // before the progress lines on stderr
  std::vector<BenchCell> cells;
  using clock = std::chrono::steady_clock;
  for (const std::string& look : o.looks)
    for (const int level : o.subdivide) {
      // The scene of the paper's Table 1: the cow in a rotation about +Y, 3
      // pixels per frame, prepared once per level and fitted to each size.
      Scene scene;
      scene.mesh = mesh_path;
      scene.subdivide = level;
      scene.field = FieldSpec::parse("rotate:0,1,0");
      if (look == "paper") apply_style(scene, Style::Paper);
      apply_bench_settings(scene, o.settings);
      const PreparedScene prepared = prepare_scene(scene);
      for (const auto& [w, h] : sizes) {
        Session session(resized(prepared, w, h));
        const TriMesh& mesh = *session.scene().mesh;
        for (const bool dynamic : {false, true}) {
          Camera camera(mesh_bounds(mesh), session.scene().camera,
                        static_cast<float>(w) / static_cast<float>(h));
          const auto frame = [&] {
            if (dynamic) camera.orbit(o.orbit);
            session.render(camera);
            session.finish();  // the renderer in force (a restart makes a new one)
          };
          session.restart();
          for (int k = 0; k < o.warmup; ++k) frame();
          BenchCell cell{look, level, mesh.triangle_count(), w, h, dynamic, 0.0, {}};
          for (int r = 0; r < o.repeats; ++r) {
            const auto start = clock::now();
            int frames = 0;
            double elapsed = 0.0;
            do {
              frame();
              ++frames;
              elapsed = std::chrono::duration<double>(clock::now() - start).count();
            } while (elapsed < o.seconds);
            cell.runs.push_back(frames / elapsed);
          }
          cell.fps = median(cell.runs);
          context.throw_if_errors();
          if (!o.quiet)
            std::fprintf(stderr, "  %s look, %s triangles, %dx%d, %s: %s fps\n", look.c_str(),
                         triangles_label(cell.triangles).c_str(), w, h,
                         dynamic ? "dynamic" : "static", fmt(cell.fps).c_str());
          cells.push_back(cell);
        }
      }
    }

  // A table per look: rows are image sizes, columns meshes, as in the paper.
  for (const std::string& look : o.looks) {
    const auto find = [&](int level, int w, int h, bool dynamic) -> const BenchCell* {
      for (const BenchCell& c : cells)
        if (c.look == look && c.subdivide == level && c.width == w && c.height == h &&
            c.dynamic == dynamic)
          return &c;
      return nullptr;
    };
    std::printf(
        "\n%s\nfps, static (dynamic); paper: GeForce4 Ti200, 2003; x: ours / paper\n\n| image |",
        look == "paper" ? "The paper's look (style paper): Table 1"
                        : "The default look (display filter along the streamline, "
                          "sharpened; docs/quality.md)");
    for (const int level : o.subdivide) {
      const BenchCell* c = find(level, sizes[0].first, sizes[0].second, false);
      std::printf(" %s triangles |", triangles_label(c ? c->triangles : 0).c_str());
    }
    std::printf("\n|---|");
    for (std::size_t i = 0; i < o.subdivide.size(); ++i) std::printf("---|");
    std::printf("\n");
    int met = 0, compared = 0;
    for (const auto& [w, h] : sizes) {
      std::printf("| %dx%d |", w, h);
      for (const int level : o.subdivide) {
        const BenchCell* s = find(level, w, h, false);
        const BenchCell* d = find(level, w, h, true);
        std::string text = fmt(s->fps) + " (" + fmt(d->fps) + ")";
        const double ps = paper_table1_fps(level, w, h, false);
        const double pd = paper_table1_fps(level, w, h, true);
        if (ps > 0.0) {
          text += "; paper " + fmt(ps) + " (" + fmt(pd) + "); x" + fmt(s->fps / ps) + " (x" +
                  fmt(d->fps / pd) + ")";
          compared += 2;
          met += (s->fps >= ps) + (d->fps >= pd);
        }
        std::printf(" %s |", text.c_str());
      }
      std::printf("\n");
    }
    if (compared > 0)
      std::printf("\n%s look: %d of %d cells at or above the paper's figure.\n", look.c_str(), met,
                  compared);
  }

  if (!o.csv.empty()) {
    std::ofstream out(o.csv);
    out << "look,triangles,subdivide,width,height,case,fps,paper_fps,runs\n";
    for (const BenchCell& c : cells) {
      out << c.look << "," << c.triangles << "," << c.subdivide << "," << c.width << "," << c.height
          << "," << (c.dynamic ? "dynamic" : "static") << "," << c.fps << ","
          << paper_table1_fps(c.subdivide, c.width, c.height, c.dynamic) << ",";
      for (std::size_t i = 0; i < c.runs.size(); ++i) out << (i ? " " : "") << c.runs[i];
      out << "\n";
    }
    if (!out) throw InputError(o.csv + ": write failed");
  }
  if (!o.json.empty()) {
    std::ofstream out(o.json);
    const auto quoted = [](const std::string& s) {
      std::string q = "\"";
      for (const char ch : s) {
        if (ch == '"' || ch == '\\') q += '\\';
        q += ch;
      }
      return q + "\"";
    };
    out << "{\n  \"mesh\": " << quoted(mesh_path) << ",\n  \"renderer\": " << quoted(renderer_name)
        << ",\n  \"cpu\": " << quoted(cpu) << ",\n  \"seconds\": " << o.seconds
        << ",\n  \"repeats\": " << o.repeats << ",\n  \"cells\": [\n";
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const BenchCell& c = cells[i];
      out << "    {\"look\": \"" << c.look << "\", \"triangles\": " << c.triangles
          << ", \"subdivide\": " << c.subdivide << ", \"width\": " << c.width
          << ", \"height\": " << c.height << ", \"case\": \"" << (c.dynamic ? "dynamic" : "static")
          << "\", \"fps\": " << c.fps
          << ", \"paper_fps\": " << paper_table1_fps(c.subdivide, c.width, c.height, c.dynamic)
          << ", \"runs\": [";
      for (std::size_t k = 0; k < c.runs.size(); ++k) out << (k ? ", " : "") << c.runs[k];
      out << "]}" << (i + 1 < cells.size() ? "," : "") << "\n";
    }
    out << "  ]\n}\n";
    if (!out) throw InputError(o.json + ": write failed");
  }
  return 0;
}

}  // namespace ibfvs::app
