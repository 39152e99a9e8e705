// read_lonlat_grid (wind: fields, relief: meshes) on every variable of a
// netCDF file (the first four), at its first and last time index, and its
// time axis made dates (the units and calendar are the file's text):
// netCDF-C in its child process (core/support/isolation.h) and the way back.

#include <algorithm>

#include "fuzz_support.h"
#include "ibfvs/core/fields/lonlat_grid.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ibfvs::fuzz::limit_readers();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ibfvs;
  const auto path = fuzz::write_input(data, size, "input.nc");
  // Every variable of a file that opens (the first four); one try of a
  // name for a file that does not.
  std::vector<std::string> names{"UWND"};
  fuzz::expect_clean_failure(path.string(), [&] {
    names = netcdf_variables(path);
    if (names.size() > 4) names.resize(4);
  });
  for (const std::string& name : names) {
    for (const std::size_t time : {std::size_t{0}, std::size_t{1}}) {
      fuzz::expect_clean_failure(path.string(), [&] {
        const LonLatGrid g = read_lonlat_grid(path, name, time);
        if (g.values.size() != g.lon.size() * g.lat.size()) fuzz::fail("grid size mismatch");
        (void)g.sample(10.0, 20.0);
      });
    }
    fuzz::expect_clean_failure(path.string(), [&] {
      const TimeAxis axis = netcdf_time_axis(path, name);
      const std::size_t n = std::min<std::size_t>(axis.values.size(), 4);
      if (n > 0 && time_labels(axis, 0, n - 1).size() != n) fuzz::fail("a label missing");
    });
  }
  return 0;
}
