// read_mesh on one format (IBFVS_FUZZ_EXTENSION: ".off", ".obj", ".ply",
// ".stl"): OpenMesh's readers in their child process (core/support/
// isolation.h), our checks of their answer, and the way back. The file
// name carries the extension, as on the command line.

#include "fuzz_support.h"
#include "ibfvs/core/mesh/mesh_io.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ibfvs::fuzz::limit_readers();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ibfvs;
  const auto path = fuzz::write_input(data, size, "input" IBFVS_FUZZ_EXTENSION);
  fuzz::expect_clean_failure(path.string(), [&] {
    MeshReadReport report;
    const TriMesh mesh = read_mesh(path, &report);
    fuzz::check_mesh(mesh);
    if (mesh.normals.size() != mesh.positions.size()) fuzz::fail("read_mesh left no normals");
  });
  return 0;
}
