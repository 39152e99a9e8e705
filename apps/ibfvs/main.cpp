// ibfvs: dense, animated, flow-aligned texture on curved surfaces
// (van Wijk, Image Based Flow Visualization for Curved Surfaces, 2003).

#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "ibfvs/bench_command.h"
#include "ibfvs/geometry_command.h"
#include "ibfvs/gl/context.h"
#include "ibfvs/options_markdown.h"
#include "ibfvs/quality_command.h"
#include "ibfvs/render_command.h"
#include "ibfvs/topology_command.h"
#include "ibfvs/view_command.h"
#ifdef IBFVS_HAVE_VTK
#include "ibfvs/vtk/vtk_io.h"
#endif

int main(int argc, char** argv) {
  ibfvs::gl::tune_process_for_rendering();
  CLI::App app{"ibfvs: image based flow visualization for curved surfaces"};
  app.require_subcommand(1, 1);
#ifdef IBFVS_HAVE_VTK
  ibfvs::vtk::install_vtk_io();
  const std::string version = std::string(IBFVS_VERSION) + " (VTK and OpenFOAM readers: VTK " +
                              ibfvs::vtk::vtk_version() + " from ParaView)";
#else
  const std::string version =
      std::string(IBFVS_VERSION) + " (built without the VTK and OpenFOAM readers)";
#endif
  app.set_version_flag("--version", version);
  auto render_options = std::make_unique<ibfvs::app::SceneOptions>();
  CLI::App* render = app.add_subcommand(
      "render", "Render IBFVS texture on a mesh headless (EGL) to a video or PNG");
  ibfvs::app::add_scene_options(*render, *render_options);
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
  auto quality_scene = std::make_unique<ibfvs::app::SceneOptions>();
  auto quality_options = std::make_unique<ibfvs::app::QualityOptions>();
  CLI::App* quality = app.add_subcommand(
      "quality",
      "Measure the picture of a scene (the same options as render): alignment with the flow, "
      "background inflow, pattern speed against the flow, flicker, contrast");
  ibfvs::app::add_quality_options(*quality, *quality_scene, *quality_options);
  auto topology_scene = std::make_unique<ibfvs::app::SceneOptions>();
  CLI::App* topology = app.add_subcommand(
      "topology",
      "Skin-friction topology of a scene's field (the same options as render): critical points, "
      "separation and attachment lines, written as VTK PolyData (-o OUT.vtp)");
  ibfvs::app::add_topology_options(*topology, *topology_scene);
  bool keys_markdown = false;
  CLI::App* keys = app.add_subcommand(
      "keys", "List every scene key (scene files; the same as render's flags) with its default");
  keys->add_flag("--markdown", keys_markdown, "As the Markdown table of docs/scenes.md");
  CLI::App* options = app.add_subcommand(
      "options", "Every command's options with their defaults, as the Markdown of docs/cli.md");
  if (argc < 2) {
    std::fputs(app.help().c_str(), stderr);
    return 1;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    // One line in the same form as every other error.
    if (*render || *geometry || *view || *bench || *keys || *quality || *options || *topology)
      std::fprintf(stderr, "ibfvs: error: %s (see ibfvs %s --help)\n", e.what(),
                   *render     ? "render"
                   : *view     ? "view"
                   : *bench    ? "bench"
                   : *keys     ? "keys"
                   : *quality  ? "quality"
                   : *options  ? "options"
                   : *topology ? "topology"
                               : "geometry");
    else
      std::fprintf(stderr,
                   "ibfvs: error: unknown command '%s' (expected render, view, geometry, bench, "
                   "quality, topology, keys or options; see ibfvs "
                   "--help)\n",
                   argv[1]);
    return 1;
  }
  try {
    if (*render)
      return ibfvs::app::run_render(
          ibfvs::app::scene_from_command_line(*render_options),
          ibfvs::is_scene_path(render_options->input) ? render_options->input : std::string());
    if (*geometry) return ibfvs::app::run_geometry(*geometry_options);
    if (*view) return ibfvs::app::run_view(*view_options);
    if (*bench) return ibfvs::app::run_bench(*bench_options);
    if (*quality) return ibfvs::app::run_quality(*quality_scene, *quality_options);
    if (*topology) return ibfvs::app::run_topology(*topology_scene);
    if (*keys) {
      std::fputs(ibfvs::app::scene_keys_table(keys_markdown).c_str(), stdout);
      return 0;
    }
    if (*options) {
      std::fputs(ibfvs::app::options_markdown(app).c_str(), stdout);
      return 0;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ibfvs: error: %s\n", ibfvs::one_line(ibfvs::app::error_line(e)).c_str());
    return 1;
  }
  return 0;
}
