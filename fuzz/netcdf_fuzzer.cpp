// read_lonlat_grid (wind: fields, relief: meshes) on every variable of a
// netCDF file (the first four), at its first and last time index.

#include <netcdf.h>

#include "fuzz_support.h"
#include "ibfvs/core/lonlat_grid.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ibfvs;
  const auto path = fuzz::write_input(data, size, "input.nc");
  std::vector<std::string> names{"UWND"};  // a file that netCDF cannot open: one try
  int nc = -1;
  if (nc_open(path.c_str(), NC_NOWRITE, &nc) == NC_NOERR) {
    int n = 0;
    nc_inq_nvars(nc, &n);
    names.clear();
    for (int v = 0; v < n && v < 4; ++v) {
      char name[NC_MAX_NAME + 1] = {};
      if (nc_inq_varname(nc, v, name) == NC_NOERR) names.emplace_back(name);
    }
    nc_close(nc);
  }
  for (const std::string& name : names) {
    for (const std::size_t time : {std::size_t{0}, std::size_t{1}}) {
      fuzz::expect_clean_failure(path.string(), [&] {
        const LonLatGrid g = read_lonlat_grid(path, name, time);
        if (g.values.size() != g.lon.size() * g.lat.size()) fuzz::fail("grid size mismatch");
        (void)g.sample(10.0, 20.0);
      });
    }
  }
  return 0;
}
