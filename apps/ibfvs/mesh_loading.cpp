#include "ibfvs/mesh_loading.h"

#include <cstdio>
#include <filesystem>
#include <optional>

#include "ibfvs/core/error.h"
#include "ibfvs/core/gpu_prep.h"
#include "ibfvs/core/mesh_io.h"
#include "ibfvs/core/procedural.h"
#include "ibfvs/core/subdivision.h"
#include "ibfvs/data_paths.h"

namespace ibfvs::app {
namespace fs = std::filesystem;

LoadedMesh load_mesh(const std::string& path, int subdivide) {
  LoadedMesh out;
  out.demo = path.empty();
  if (out.demo) {
    std::optional<fs::path> demo = find_data_file("meshes/bunny00.off");
    if (!demo) demo = find_data_file("meshes/cow.off");
    if (demo) {
      out.mesh = read_mesh(*demo);
      out.name = demo->filename().string();
    } else {
      std::fprintf(stderr,
                   "ibfvs: the fetched meshes are missing (%s); using a procedural torus "
                   "instead. Run scripts/fetch_data.sh for the bunny.\n",
                   (data_dir() / "meshes").c_str());
      out.mesh = make_torus(1.0f, 0.4f, 160, 64);
      out.name = "procedural torus";
    }
  } else {
    MeshReadReport report;
    out.mesh = read_mesh(path, &report);
    for (const std::string& w : report.warnings)
      std::fprintf(stderr, "ibfvs: warning: %s\n", w.c_str());
    out.name = path;
  }
  if (subdivide > 0) {
    try {
      out.mesh = loop_subdivide(out.mesh, subdivide);
    } catch (const InputError& e) {
      throw InputError(out.name + ": " + e.what());
    }
  }
  optimize_for_gpu(out.mesh);
  return out;
}

}  // namespace ibfvs::app
