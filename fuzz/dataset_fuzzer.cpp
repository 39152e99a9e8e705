// read_dataset on one VTK format (IBFVS_FUZZ_EXTENSION: ".vtk" legacy, ".vtp"
// and ".vtu" XML): ParaView's VTK readers in their child process
// (core/support/isolation.h), our conversion of their surfaces and arrays to a
// TriMesh, and the way back. A crash inside VTK ends only the child and is
// an InputError here; what this harness finds is ours.
#include "fuzz_support.h"
#include "ibfvs/core/mesh/dataset_io.h"
#include "ibfvs/vtk/vtk_io.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ibfvs::fuzz::limit_readers();
  ibfvs::vtk::install_vtk_io();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ibfvs;
  const auto path = fuzz::write_input(data, size, "input" IBFVS_FUZZ_EXTENSION);
  fuzz::expect_clean_failure(path.string(), [&] {
    const Dataset d = read_dataset({path, {}});
    fuzz::check_mesh(d.mesh);
  });
  return 0;
}
