// read_dataset on one VTK format (IBFVS_FUZZ_EXTENSION: ".vtk" legacy, ".vtp"
// and ".vtu" XML): ParaView's VTK readers and our conversion of their
// surfaces and arrays to a TriMesh.

#include "fuzz_support.h"
#include "ibfvs/core/dataset_io.h"
#include "ibfvs/vtk/vtk_io.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
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
