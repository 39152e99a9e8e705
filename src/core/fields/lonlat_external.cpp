// The lon/lat grids in builds without netCDF-C (IBFVS_WITH_NETCDF=OFF: the
// pip package): read by the reader set_lonlat_reader gave, its result
// checked here as lonlat_netcdf.cpp checks what netCDF-C reads.
#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>
#include <utility>

#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

std::mutex reader_mutex;
LonLatReader& reader() {
  static LonLatReader r;
  return r;
}

LonLatReader current(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw InputError(one_line(path.string() + ": no such file"));
  std::lock_guard<std::mutex> lock(reader_mutex);
  if (!reader().read || !reader().variables || !reader().time_axis)
    throw InputError(one_line(
        path.string() +
        ": this build of ibfvs has no netCDF reader of its own; in Python it reads netCDF "
        "through xarray (pip install 'ibfvs[netcdf]'), or read the file there and pass the "
        "vectors as arrays; the Debian build (README.md) reads it itself"));
  return reader();
}

void check_grid(const LonLatGrid& g, const std::filesystem::path& path, std::size_t time_index) {
  const auto fail = [&](const std::string& problem) {
    throw InputError(one_line(path.string() + ": " + problem));
  };
  const std::size_t nx = g.lon.size(), ny = g.lat.size();
  if (nx < 2 || ny < 2) fail("'" + g.name + "' is not a grid (fewer than 2 x 2 points)");
  if (g.values.size() != nx * ny)
    fail("'" + g.name + "' has " + std::to_string(g.values.size()) + " values for " +
         std::to_string(ny) + " x " + std::to_string(nx) + " points");
  if (!std::is_sorted(g.lon.begin(), g.lon.end()) || g.lon.front() == g.lon.back())
    fail("the longitudes of '" + g.name + "' do not increase");
  if (!std::all_of(g.lat.begin(), g.lat.end(), [](double v) { return std::isfinite(v); }) ||
      !std::all_of(g.lon.begin(), g.lon.end(), [](double v) { return std::isfinite(v); }))
    fail("the coordinates of '" + g.name + "' are not all finite");
  if (g.time_steps == 0 || time_index >= g.time_steps)
    fail("time index " + std::to_string(time_index) + " is out of range for '" + g.name + "' (" +
         std::to_string(g.time_steps) + " time step" + (g.time_steps == 1 ? "" : "s") +
         ", counted from 0)");
}

}  // namespace

bool netcdf_built_in() {
  return false;
}

void set_lonlat_reader(LonLatReader r) {
  std::lock_guard<std::mutex> lock(reader_mutex);
  reader() = std::move(r);
}

std::vector<std::string> netcdf_variables(const std::filesystem::path& path) {
  return current(path).variables(path);
}

LonLatGrid read_lonlat_grid(const std::filesystem::path& path, const std::string& variable,
                            std::size_t time_index) {
  LonLatGrid g = current(path).read(path, variable, time_index);
  g.name = variable;
  check_grid(g, path, time_index);
  for (float& v : g.values)
    if (!std::isfinite(v)) v = std::nanf("");
  return g;
}

TimeAxis netcdf_time_axis(const std::filesystem::path& path, const std::string& variable) {
  return current(path).time_axis(path, variable);
}

}  // namespace ibfvs
