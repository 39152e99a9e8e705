// ibfvs: dense, animated, flow-aligned texture on curved surfaces
// (van Wijk, Image Based Flow Visualization for Curved Surfaces, 2003).

#include <malloc.h>
#include <stdlib.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "ibfvs/bench_command.h"
#include "ibfvs/geometry_command.h"
#include "ibfvs/render_command.h"
#include "ibfvs/scene.h"
#include "ibfvs/styles.h"
#include "ibfvs/view_command.h"

int main(int argc, char** argv) {
  // Mesa's llvmpipe allocates and frees large buffers every frame; glibc's
  // default trimming hands them back to the kernel, and every frame then
  // page-faults them in again (a quarter of the time in kernel page faults, 3x
  // slower on the 75K-triangle bunny). Keep freed memory for reuse instead.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  // llvmpipe runs one rasteriser thread per core. On two cores a third thread
  // keeps both busy while one waits (the subdivided cow at 512x512: 150-180 ->
  // 190-205 fps with glFinish per frame, no change at other sizes). Measured
  // on two cores only, so only set there; the user's LP_NUM_THREADS wins and
  // GPU drivers ignore it.
  if (std::thread::hardware_concurrency() == 2) setenv("LP_NUM_THREADS", "3", 0);
  CLI::App app{"ibfvs: image based flow visualization for curved surfaces"};
  app.require_subcommand(1, 1);
  app.set_version_flag("--version", IBFVS_VERSION);
  auto render_options = std::make_unique<ibfvs::app::RenderOptions>();
  CLI::App* render = app.add_subcommand(
      "render", "Render IBFVS texture on a mesh headless (EGL) to a video or PNG");
  ibfvs::app::add_render_options(*render, *render_options);
  auto view_options = std::make_unique<ibfvs::app::ViewOptions>();
  CLI::App* view = app.add_subcommand(
      "view",
      "Open an interactive window (GLFW, OpenGL 4.5): the same options as render, plus mouse, "
      "keyboard (h: help) and a parameter panel");
  ibfvs::app::add_view_options(*view, *view_options);
  auto bench_options = std::make_unique<ibfvs::app::BenchOptions>();
  CLI::App* bench = app.add_subcommand(
      "bench",
      "The paper's Table 1: fps on the Loop-subdivided cow at three image sizes, static and "
      "rotating, beside the 2003 figures");
  ibfvs::app::add_bench_options(*bench, *bench_options);
  auto geometry_options = std::make_unique<ibfvs::app::GeometryOptions>();
  CLI::App* geometry = app.add_subcommand(
      "geometry",
      "Normals, principal curvatures and directions (Goldfeather-Interrante), Loop "
      "subdivision: print a summary and write a PLY");
  ibfvs::app::add_geometry_options(*geometry, *geometry_options);
  if (argc < 2) {
    std::fputs(app.help().c_str(), stderr);
    return 1;
  }
  // `ibfvs render SCENE.toml [options]`: the scene's settings go first, so the
  // command line's own options override them.
  std::vector<std::string> args(argv + 1, argv + argc);
  const bool renders = !args.empty() && (args[0] == "render" || args[0] == "view");
  if (args.size() >= 2 && renders && ibfvs::app::is_scene_path(args[1])) {
    try {
      std::vector<std::string> scene = ibfvs::app::scene_arguments(args[1]);
      args.erase(args.begin() + 1);
      args.insert(args.begin() + 1, scene.begin(), scene.end());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "ibfvs: error: %s\n", e.what());
      return 1;
    }
  }
  // `--style NAME` (given or from the scene): its defaults go before all else.
  if (renders) {
    std::string style;
    for (std::size_t i = 1; i < args.size(); ++i) {
      if (args[i] == "--style" && i + 1 < args.size()) style = args[i + 1];
      if (args[i].rfind("--style=", 0) == 0) style = args[i].substr(8);
    }
    if (!style.empty()) {
      try {
        const std::vector<std::string> defaults = ibfvs::app::style_arguments(style);
        args.insert(args.begin() + 1, defaults.begin(), defaults.end());
      } catch (const std::exception& e) {
        std::fprintf(stderr, "ibfvs: error: %s\n", e.what());
        return 1;
      }
    }
  }
  if (!args.empty() && args[0] == "view")  // to save the state as a scene later
    view_options->arguments.assign(args.begin() + 1, args.end());
  std::reverse(args.begin(), args.end());  // CLI11 takes them last-first
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    // One line in the same form as every other error.
    if (*render || *geometry || *view || *bench)
      std::fprintf(stderr, "ibfvs: error: %s (see ibfvs %s --help)\n", e.what(),
                   *render  ? "render"
                   : *view  ? "view"
                   : *bench ? "bench"
                            : "geometry");
    else
      std::fprintf(
          stderr,
          "ibfvs: error: unknown command '%s' (expected render, view, geometry or bench; see ibfvs "
          "--help)\n",
          argv[1]);
    return 1;
  }
  try {
    if (*render) return ibfvs::app::run_render(*render_options);
    if (*geometry) return ibfvs::app::run_geometry(*geometry_options);
    if (*view) return ibfvs::app::run_view(*view_options);
    if (*bench) return ibfvs::app::run_bench(*bench_options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ibfvs: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
