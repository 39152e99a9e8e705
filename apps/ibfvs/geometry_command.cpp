#include "ibfvs/geometry_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <CLI/CLI.hpp>

#include "ibfvs/core/geometry/curvature.h"
#include "ibfvs/core/mesh/dataset_io.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/scene/mesh_source.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"
#include "ibfvs/render_command.h"

namespace ibfvs::app {
namespace fs = std::filesystem;

void add_geometry_options(CLI::App& cmd, GeometryOptions& o) {
  cmd.add_option("mesh", o.mesh,
                 "Triangle mesh: .off .obj .ply .stl, or a dataset: " + dataset_extensions_text() +
                     ", an OpenFOAM case")
      ->required();
  cmd.add_option("--subdivide", o.subdivide,
                 "Loop subdivision levels (0..12, as many as memory holds)")
      ->capture_default_str();
  cmd.add_option("-o,--out", o.out,
                 "Write a PLY or VTK .vtp (for ParaView) with per-vertex nx ny nz (refined "
                 "normals), kmin kmax, dminx dminy "
                 "dminz, dmaxx dmaxy dmaxz (principal curvatures and directions), and any vx vy "
                 "vz and scalars of the input. Default: only print the summary");
  cmd.add_flag("--ascii", o.ascii, "Write ASCII PLY instead of binary");
  cmd.add_option("--curvature-fit", o.fit,
                 "auto: the quartic jet on exact meshes (CAD, subdivision, simulation), the cubic "
                 "fit with normals on noisy ones (scans); quartic or cubic forces one")
      ->check(CLI::IsMember({"auto", "quartic", "cubic"}))
      ->capture_default_str();
  cmd.add_flag("--quiet,-q", o.quiet, "No summary");
}

namespace {

// The value below which a fraction `q` of `v` lies.
float percentile(std::vector<float> v, double q) {
  if (v.empty()) return 0.0f;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

int run_geometry(const GeometryOptions& o) {
  if (o.subdivide < 0 || o.subdivide > 12)
    throw InputError("--subdivide: levels must be between 0 and 12");
  if (!o.out.empty()) {
    const std::string ext = lower_extension(o.out);
    if (ext != ".ply" && ext != ".vtp")
      throw InputError("--out: must be a .ply or .vtp file, got '" + o.out + "'");
    if (ext == ".vtp") require_dataset_io(o.out, "--out");
    if (same_file(o.out, o.mesh))
      throw InputError("--out: " + o.out + " is the input mesh; writing it would destroy it");
    ensure_parent(o.out, "--out");
  }
  using clock = std::chrono::steady_clock;
  const auto seconds = [](clock::time_point a, clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  const auto t0 = clock::now();
  // Read and subdivide; no GPU vertex order, so that written per-vertex data
  // lines up with the input's vertices (subdivision makes new ones anyway).
  LoadedMesh loaded = load_mesh(o.mesh, o.subdivide, false);
  for (const std::string& w : loaded.warnings)
    std::fprintf(stderr, "ibfvs: warning: %s\n", w.c_str());
  TriMesh& mesh = loaded.mesh;
  const auto t1 = clock::now();
  compute_vertex_normals(mesh);
  CurvatureOptions curvature_options;
  curvature_options.fit = o.fit == "quartic" ? CurvatureFit::quartic
                          : o.fit == "cubic" ? CurvatureFit::cubic_with_normals
                                             : CurvatureFit::automatic;
  const Curvature curvature = compute_curvature(mesh, curvature_options);
  const auto t2 = clock::now();
  store_curvature(mesh, curvature);
  if (!o.out.empty()) {
    if (lower_extension(o.out) == ".vtp")
      write_polydata(mesh, nullptr, o.out);
    else
      write_ply(mesh, o.out, !o.ascii);
  }
  const auto t3 = clock::now();

  if (!o.quiet) {
    const Topology top = analyze_topology(mesh);
    std::string shape = top.boundary_loops == 0
                            ? "closed"
                            : std::to_string(top.boundary_loops) + " boundary loop" +
                                  (top.boundary_loops == 1 ? "" : "s");
    if (top.nonmanifold_edges)
      shape += ", " + std::to_string(top.nonmanifold_edges) + " non-manifold edges";
    // Which fit, and why when it was chosen (see CurvatureFit::automatic).
    std::string fit =
        curvature.fit == CurvatureFit::quartic ? "quartic jet" : "cubic fit with normals";
    if (curvature_options.fit == CurvatureFit::automatic) {
      char why[96];
      std::snprintf(why, sizeof why, " (the mesh looks %s: %.1f)",
                    curvature.fit == CurvatureFit::quartic ? "exact" : "noisy",
                    static_cast<double>(curvature.noise_ratio));
      fit += why;
    }
    if (curvature.fit == CurvatureFit::quartic && curvature.quartic_vertices < mesh.vertex_count())
      fit += ", the cubic at " + std::to_string(mesh.vertex_count() - curvature.quartic_vertices) +
             " vertices";
    std::printf(
        "%s: %zu vertices, %zu triangles%s; %s. kmin from %.4g to %.4g (1st-99th percentile "
        "%.4g..%.4g), kmax from %.4g to %.4g (%.4g..%.4g) by the %s%s. Read and subdivision "
        "%.3f s; normals and curvature %.3f s%s.\n",
        o.mesh.c_str(), mesh.vertex_count(), mesh.triangle_count(),
        o.subdivide ? (" after " + std::to_string(o.subdivide) + " Loop subdivisions").c_str() : "",
        shape.c_str(), *std::min_element(curvature.kmin.begin(), curvature.kmin.end()),
        *std::max_element(curvature.kmin.begin(), curvature.kmin.end()),
        percentile(curvature.kmin, 0.01), percentile(curvature.kmin, 0.99),
        *std::min_element(curvature.kmax.begin(), curvature.kmax.end()),
        *std::max_element(curvature.kmax.begin(), curvature.kmax.end()),
        percentile(curvature.kmax, 0.01), percentile(curvature.kmax, 0.99), fit.c_str(),
        curvature.fallback_vertices
            ? (", " + std::to_string(curvature.fallback_vertices) +
               (curvature.fallback_vertices == 1 ? " vertex" : " vertices") + " by a lower degree")
                  .c_str()
            : "",
        seconds(t0, t1), seconds(t1, t2),
        o.out.empty()
            ? ""
            : ("; wrote " + o.out + " in " + std::to_string(seconds(t2, t3)).substr(0, 5) + " s")
                  .c_str());
  }
  return 0;
}

}  // namespace ibfvs::app
