#pragma once
// Internal to the core: the header of a classic netCDF file (CDF-1, CDF-2
// "64-bit offset", CDF-5 "64-bit data") walked before netCDF-C opens it.
// netCDF-C 4.9 allocates what the header declares before it knows the file
// holds it, and fuzzing found it asking for tens of GiB and spinning for
// minutes on a header of a few hundred bytes. This walk, as the format
// specification gives it, refuses such a header (and a file cut short
// before its variables' data, which netCDF-C would read as zeros) with an
// InputError naming the file and the problem. netCDF-4 (HDF5) files are
// left to the library.

#include <filesystem>

namespace ibfvs::detail {

/// Throws InputError when `path` is a classic netCDF file whose header is
/// malformed, declares more than the file holds, or whose fixed-size
/// variables' data run past the end of the file. Other files pass.
void precheck_netcdf(const std::filesystem::path& path);

}  // namespace ibfvs::detail
