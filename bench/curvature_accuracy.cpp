// Curvature accuracy on irregular meshes with known curvature, side by side:
// ibfvs's fit and CGAL's Monge jet fitting on the same meshes. Prints the
// table of docs/geometry.md.
//
//   build/bench/ibfvs_curvature_accuracy [--all]
//
// --all adds the candidate settings that were measured when choosing the
// defaults (docs/geometry.md).

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "ibfvs/core/geometry/curvature.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "support/curvature_surfaces.h"

namespace ibfvs {
namespace {

struct Method {
  std::string name;
  std::function<Curvature(const TriMesh&)> run;
};

void report(const test::TestSurface& s, const std::vector<Method>& methods) {
  std::printf("\n%s: %zu vertices, %zu triangles\n", s.name.c_str(), s.mesh.vertex_count(),
              s.mesh.triangle_count());
  std::printf(
      "| method | kmax rel. error median / 95th | kmin abs. error median / 95th |"
      " kmax direction median / 95th | ms |\n|---|---|---|---|---|\n");
  for (const Method& m : methods) {
    const auto t0 = std::chrono::steady_clock::now();
    const Curvature c = m.run(s.mesh);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (c.kmin.empty()) continue;  // CGAL missing
    const test::CurvatureErrors e = test::curvature_errors(s, c);
    std::printf("| %s | %.3f%% / %.3f%% | %.5f / %.5f | %.3f / %.3f deg | %.0f |", m.name.c_str(),
                100 * e.kmax_rel_median, 100 * e.kmax_rel_p95, e.kmin_abs_median, e.kmin_abs_p95,
                e.dir_median, e.dir_p95, ms);
    if (e.non_finite) std::printf(" %zu NaN", e.non_finite);
    std::printf("\n");
  }
}

}  // namespace
}  // namespace ibfvs

int main(int argc, char** argv) {
  using namespace ibfvs;
  const bool all = argc > 1 && std::strcmp(argv[1], "--all") == 0;
  std::vector<Method> methods;
  methods.push_back({"ibfvs (default)", [](const TriMesh& m) { return compute_curvature(m); }});
  if (all) {
    const auto with = [](CurvatureFit fit, float radius) {
      return [=](const TriMesh& m) {
        CurvatureOptions o;
        o.fit = fit, o.weight_radius = radius;
        return compute_curvature(m, o);
      };
    };
    methods.push_back({"ibfvs quartic", with(CurvatureFit::quartic, 0.6f)});
    methods.push_back({"ibfvs quartic, equal weights", with(CurvatureFit::quartic, 0.0f)});
    methods.push_back({"ibfvs quartic, weights 0.5", with(CurvatureFit::quartic, 0.5f)});
    methods.push_back({"ibfvs quartic, weights 0.7", with(CurvatureFit::quartic, 0.7f)});
    methods.push_back({"ibfvs quartic, weights 0.8", with(CurvatureFit::quartic, 0.8f)});
    methods.push_back({"ibfvs cubic with normals", with(CurvatureFit::cubic_with_normals, 0.6f)});
  }
  methods.push_back({"CGAL jet fitting d4 2-ring",
                     [](const TriMesh& m) { return test::cgal_jet_fitting(m, 4, 2); }});
  methods.push_back({"CGAL jet fitting d3 2-ring",
                     [](const TriMesh& m) { return test::cgal_jet_fitting(m, 3, 2); }});

  report(test::jittered_torus(1.0f, 0.35f, 113, 40, 1.0f / 3.0f, 1), methods);
  {
    test::TestSurface noisy = test::jittered_torus(1.0f, 0.35f, 113, 40, 1.0f / 3.0f, 1);
    test::add_normal_noise(noisy, std::getenv("NOISE") ? std::atof(std::getenv("NOISE")) : 0.01f,
                           5);
    report(noisy, methods);
  }
  report(test::jittered_torus(1.0f, 0.4f, 160, 64, 0.0f, 1), methods);
  report(test::jittered_ellipsoid({1.0f, 0.75f, 0.5f}, 4, 1.0f / 3.0f, 2), methods);
  if (test::have_cgal()) {
    report(test::random_sphere(1.0f, 3000, 3), methods);
    report(test::loop_limit_surface(test::random_sphere(1.0f, 60, 4).mesh, 3,
                                    "Loop limit of a 60-point random hull"),
           methods);
  }
  const std::filesystem::path cow = std::filesystem::path(IBFVS_BENCH_DATA_DIR) / "meshes/cow.off";
  if (std::filesystem::exists(cow))
    report(test::loop_limit_surface(read_mesh(cow), 2, "Loop limit of the cow (2 levels)"),
           methods);
  return 0;
}
