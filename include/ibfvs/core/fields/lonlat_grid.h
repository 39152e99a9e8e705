#pragma once
// Gridded geophysical data on longitude/latitude grids, read from netCDF
// (paper section 4.1, figure 6: the wind on the earth), and mapped onto a
// sphere: longitude 0 at +Z, east towards +X, north pole at +Y.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ibfvs/core/fields/cf_time.h"
#include "ibfvs/core/mesh/mesh.h"

namespace ibfvs {

/// One 2D slice of a variable on a longitude/latitude grid.
struct LonLatGrid {
  std::string name;            ///< variable name
  std::string units;           ///< its units attribute, if any
  std::vector<double> lon;     ///< degrees east, one per column, increasing
  std::vector<double> lat;     ///< degrees north, one per row, increasing or decreasing
  std::vector<float> values;   ///< row-major (lat, lon); NaN where the file says missing
  std::size_t time_steps = 1;  ///< length of the time dimension (1 if none)

  /// Bilinear in longitude (periodic when the grid spans the globe) and
  /// latitude (clamped at the outer rows). NaN when a neighbour is missing.
  [[nodiscard]] float sample(double lon_deg, double lat_deg) const;
};

/// The names of the variables in a netCDF file, in file order. Throws
/// InputError naming the file if it cannot be opened or is malformed.
std::vector<std::string> netcdf_variables(const std::filesystem::path& path);

/// Reads `variable` at `time_index` (for variables with a leading time
/// dimension) from a netCDF file. The last two dimensions are latitude and
/// longitude; their coordinate variables give the degrees. Missing values
/// (_FillValue, missing_value) become NaN; scale_factor and add_offset are
/// applied. Throws InputError naming the file for a missing file or
/// variable, a variable that is not a lon/lat grid, or a time index out of
/// range.
LonLatGrid read_lonlat_grid(const std::filesystem::path& path, const std::string& variable,
                            std::size_t time_index = 0);

/// The time axis of `variable`: the coordinate variable of its leading
/// (time) dimension, with that variable's `units` and `calendar` attributes
/// (time_labels makes them dates). Empty for a variable without a time
/// dimension, or whose time dimension has no coordinate variable. Throws
/// InputError naming the file as read_lonlat_grid does.
TimeAxis netcdf_time_axis(const std::filesystem::path& path, const std::string& variable);

/// True when this build reads netCDF itself (netCDF-C, the Debian build);
/// otherwise netcdf_variables, read_lonlat_grid and netcdf_time_axis go to
/// the reader that set_lonlat_reader gave (the pip package's: Python's
/// xarray).
bool netcdf_built_in();

/// A reader of netCDF lon/lat grids from outside the library, for builds
/// without netCDF-C. `read` returns the grid as read_lonlat_grid describes
/// it; the library checks its shape and coordinates as it checks its own.
/// Either function throws InputError (naming the file) when it cannot read.
struct LonLatReader {
  std::function<std::vector<std::string>(const std::filesystem::path&)> variables;
  std::function<LonLatGrid(const std::filesystem::path&, const std::string&, std::size_t)> read;
  std::function<TimeAxis(const std::filesystem::path&, const std::string&)> time_axis;
};
/// Sets the reader for builds without netCDF-C (an empty one: none); the
/// Debian build, which reads netCDF itself, never calls it.
void set_lonlat_reader(LonLatReader reader);

/// A geodesic sphere of radius 1: an icosahedron Loop-subdivided `level`
/// times and projected onto the sphere, with exact normals (20 * 4^level triangles).
TriMesh make_globe(int level);

/// Longitude and latitude (degrees) of a point on the sphere about the origin.
void to_lonlat(const glm::vec3& p, double& lon_deg, double& lat_deg);

/// Per-vertex tangent vectors u * east + v * north from eastward and northward
/// components on a grid. Vertices where either is missing get a zero vector
/// and `valid[i] = 0` (else 1). Throws InputError when the two grids differ.
std::vector<glm::vec3> lonlat_vectors(const TriMesh& globe, const LonLatGrid& east,
                                      const LonLatGrid& north, std::vector<float>* valid = nullptr);

/// Per-vertex samples of a grid (NaN where missing).
std::vector<float> lonlat_scalars(const TriMesh& globe, const LonLatGrid& grid);

}  // namespace ibfvs
