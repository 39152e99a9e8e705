// Mesh preprocessing of paper section 5 ("for meshes in the order of 100K
// triangles this preprocessing typically takes a few seconds"): vertex
// normals, curvature and principal directions, vertex-cache order; and the
// fit of a moving mesh's motion between two saved steps (each vertex's
// screw, core/geometry/rigid_motion.h: what a step change of a moving
// series costs on the CPU). On a
// procedural torus of 100K triangles and, when the data is fetched, on the
// cow subdivided twice (92,864 triangles, the paper's largest Table 1 mesh).
//
//   build/bench/ibfvs_preprocess_bench [--benchmark_filter=...]

#include <cmath>
#include <filesystem>
#include <random>

#include <benchmark/benchmark.h>
#include <omp.h>

#include "ibfvs/core/geometry/curvature.h"
#include "ibfvs/core/geometry/rigid_motion.h"
#include "ibfvs/core/mesh/gpu_prep.h"
#include "ibfvs/core/mesh/mesh_io.h"
#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/mesh/subdivision.h"

namespace ibfvs {
namespace {

const TriMesh& torus_100k() {
  static const TriMesh m = make_torus(1.0f, 0.4f, 500, 100);  // 100,000 triangles
  return m;
}

const TriMesh* cow_92k() {
  static const TriMesh* m = [] {
    const std::filesystem::path p = std::filesystem::path(IBFVS_BENCH_DATA_DIR) / "meshes/cow.off";
    if (!std::filesystem::exists(p)) return static_cast<TriMesh*>(nullptr);
    return new TriMesh(loop_subdivide(read_mesh(p), 2));
  }();
  return m;
}

// The same torus as a scan would give it: every vertex moved along its
// normal by noise of 1% of an edge, normals recomputed. Curvature then takes
// its other path (the cubic fit with normals).
const TriMesh& noisy_torus_100k() {
  static const TriMesh m = [] {
    TriMesh t = make_torus(1.0f, 0.4f, 500, 100);
    std::mt19937 rng(1);
    std::normal_distribution<float> noise(0.0f, 0.01f * 2.0f * 3.14159265f * 0.4f / 100.0f);
    for (std::size_t i = 0; i < t.vertex_count(); ++i) t.positions[i] += noise(rng) * t.normals[i];
    compute_vertex_normals(t);
    return t;
  }();
  return m;
}

const TriMesh* mesh_for(int which) {
  return which == 0 ? &torus_100k() : which == 2 ? &noisy_torus_100k() : cow_92k();
}

void set_label(benchmark::State& state, const TriMesh& m) {
  const char* names[] = {"torus ", "cow/2 ", "noisy torus "};
  state.SetLabel(names[state.range(0)] + std::to_string(m.triangle_count()) + " triangles, " +
                 std::to_string(state.range(1)) + " threads");
  state.counters["triangles/s"] = benchmark::Counter(static_cast<double>(m.triangle_count()),
                                                     benchmark::Counter::kIsIterationInvariantRate);
}

void BM_Normals(benchmark::State& state) {
  const TriMesh* src = mesh_for(static_cast<int>(state.range(0)));
  if (!src) return state.SkipWithError("cow.off not fetched (scripts/fetch_data.sh)");
  TriMesh m = *src;
  for (auto _ : state) {
    compute_vertex_normals(m);
    benchmark::DoNotOptimize(m.normals.data());
  }
  set_label(state, m);
}

void BM_Curvature(benchmark::State& state) {
  const TriMesh* src = mesh_for(static_cast<int>(state.range(0)));
  if (!src) return state.SkipWithError("cow.off not fetched (scripts/fetch_data.sh)");
  omp_set_num_threads(static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(compute_curvature(*src).kmin.data());
  set_label(state, *src);
}

void BM_CacheOrder(benchmark::State& state) {
  const TriMesh* src = mesh_for(static_cast<int>(state.range(0)));
  if (!src) return state.SkipWithError("cow.off not fetched (scripts/fetch_data.sh)");
  for (auto _ : state) {
    state.PauseTiming();
    TriMesh m = *src;
    state.ResumeTiming();
    optimize_for_gpu(m);
    benchmark::DoNotOptimize(m.triangles.data());
  }
  set_label(state, *src);
}

// Everything `ibfvs render` and `ibfvs geometry` do after reading.
void BM_Preprocess(benchmark::State& state) {
  const TriMesh* src = mesh_for(static_cast<int>(state.range(0)));
  if (!src) return state.SkipWithError("cow.off not fetched (scripts/fetch_data.sh)");
  omp_set_num_threads(static_cast<int>(state.range(1)));
  for (auto _ : state) {
    state.PauseTiming();
    TriMesh m = *src;
    state.ResumeTiming();
    compute_vertex_normals(m);
    store_curvature(m, compute_curvature(m));
    optimize_for_gpu(m);
    benchmark::DoNotOptimize(m.triangles.data());
  }
  set_label(state, *src);
}

// The mesh turned 3 degrees about an axis off its centre: every vertex's
// one-ring fitted and written as a screw.
void BM_SurfaceMotion(benchmark::State& state) {
  const TriMesh* src = mesh_for(static_cast<int>(state.range(0)));
  if (!src) return state.SkipWithError("cow.off not fetched (scripts/fetch_data.sh)");
  omp_set_num_threads(static_cast<int>(state.range(1)));
  std::vector<glm::vec3> turned = src->positions;
  const float c = std::cos(0.05236f), s = std::sin(0.05236f);
  for (glm::vec3& p : turned) p = {c * (p.x - 0.3f) - s * p.y, s * (p.x - 0.3f) + c * p.y, p.z};
  for (auto _ : state)
    benchmark::DoNotOptimize(
        fit_surface_motion(src->triangles, src->positions, turned).omega.data());
  set_label(state, *src);
  state.counters["vertices/s"] = benchmark::Counter(static_cast<double>(src->vertex_count()),
                                                    benchmark::Counter::kIsIterationInvariantRate);
}

const int threads = omp_get_num_procs();
BENCHMARK(BM_Normals)->Args({0, 1})->Args({1, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Curvature)
    ->Args({0, 1})
    ->Args({0, threads})
    ->Args({1, 1})
    ->Args({1, threads})
    ->Args({2, 1})
    ->Args({2, threads})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_CacheOrder)->Args({0, 1})->Args({1, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SurfaceMotion)
    ->Args({0, 1})
    ->Args({0, threads})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Preprocess)
    ->Args({0, 1})
    ->Args({0, threads})
    ->Args({1, 1})
    ->Args({1, threads})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace ibfvs

BENCHMARK_MAIN();
