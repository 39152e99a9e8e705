// The lon/lat grids read with netCDF-C, in a child process (the Debian
// build: IBFVS_WITH_NETCDF).
#include "ibfvs/core/fields/lonlat_grid.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <functional>
#include <utility>

#include <fcntl.h>
#include <netcdf.h>
#include <netcdf_mem.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/isolation.h"
#include "ibfvs/core/support/limits.h"

namespace ibfvs {
namespace {

// The file, mapped, opened by netCDF-C from memory; closed and unmapped on
// every path out. From memory, netCDF-C refuses to read past the end of a
// file cut short (NC_EPERM); from the file it would read zeros there.
class NcFile {
 public:
  explicit NcFile(const std::filesystem::path& path) : path_(path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail("no such file");
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) fail(std::string("cannot open the file (") + std::strerror(errno) + ")");
    struct stat st {};
    if (::fstat(fd, &st) == 0 && st.st_size > 0) {
      size_ = static_cast<std::size_t>(st.st_size);
      void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
      map_ = p == MAP_FAILED ? nullptr : p;
    }
    ::close(fd);
    if (!map_) fail(size_ == 0 ? "the file is empty" : "cannot map the file");
    const int status = nc_open_mem(path.c_str(), NC_NOWRITE, size_, map_, &id_);
    if (status != NC_NOERR)
      fail(std::string("not a readable netCDF file (") + nc_strerror(status) + ")");
  }
  ~NcFile() {
    if (id_ >= 0) nc_close(id_);
    if (map_) ::munmap(map_, size_);
  }
  NcFile(const NcFile&) = delete;
  NcFile& operator=(const NcFile&) = delete;
  [[nodiscard]] int id() const { return id_; }
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(one_line(path_.string() + ": " + problem));  // names are the file's bytes
  }
  void check(int status, const std::string& what) const {
    // From memory, a read past the end is EPERM (a system error number).
    if (status == EPERM) fail(what + ": the file ends before its data (cut short)");
    if (status != NC_NOERR) fail(what + ": " + nc_strerror(status));
  }

 private:
  std::filesystem::path path_;
  void* map_ = nullptr;
  std::size_t size_ = 0;
  int id_ = -1;
};

std::vector<std::string> variable_names(int nc) {
  int n = 0;
  nc_inq_nvars(nc, &n);
  std::vector<std::string> out;
  for (int v = 0; v < n; ++v) {
    char name[NC_MAX_NAME + 1] = {};
    nc_inq_varname(nc, v, name);
    out.emplace_back(name);
  }
  return out;
}

std::string variable_list(int nc) {
  std::string out;
  for (const std::string& name : variable_names(nc)) out += (out.empty() ? "" : ", ") + name;
  return out;
}

bool attribute(int nc, int var, const char* name, double& value) {
  nc_type type;
  std::size_t len = 0;
  if (nc_inq_att(nc, var, name, &type, &len) != NC_NOERR || len != 1 || type == NC_CHAR)
    return false;
  return nc_get_att_double(nc, var, name, &value) == NC_NOERR;
}

// The coordinate values of dimension `dim`: its coordinate variable, or 0..n-1.
std::vector<double> coordinates(const NcFile& file, int dim, std::size_t n) {
  const int nc = file.id();
  char name[NC_MAX_NAME + 1] = {};
  nc_inq_dimname(nc, dim, name);
  std::vector<double> out(n);
  int var = -1;
  if (nc_inq_varid(nc, name, &var) == NC_NOERR) {
    const int status = nc_get_var_double(nc, var, out.data());
    if (status == NC_NOERR) return out;
    if (status == EPERM) file.check(status, std::string("reading '") + name + "'");
  }
  for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<double>(i);
  return out;
}

// A text attribute of a variable ("" where it has none).
std::string text_attribute(int nc, int var, const char* name) {
  nc_type type;
  std::size_t len = 0;
  if (nc_inq_att(nc, var, name, &type, &len) != NC_NOERR || type != NC_CHAR) return {};
  std::string out(len, '\0');
  if (nc_get_att_text(nc, var, name, out.data()) != NC_NOERR) return {};
  while (!out.empty() && out.back() == '\0') out.pop_back();
  return out;
}

// netCDF-C reads in a child process: a crash, a runaway allocation or a loop
// in it is one error line (support/isolation.h), and nothing of ours
// re-parses the file in front of it.
IsolatedBytes read_isolated(const std::filesystem::path& path,
                            const std::function<void(ByteWriter&)>& work) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw InputError(one_line(path.string() + ": no such file"));
  return run_isolated(one_line(path.string()), "netCDF-C", work);
}

// A variable's id and its number of dimensions; a missing one fails
// naming the variables the file has.
std::pair<int, int> find_variable(const NcFile& file, const std::string& variable) {
  const int nc = file.id();
  int var = -1, ndims = 0;
  if (nc_inq_varid(nc, variable.c_str(), &var) != NC_NOERR)
    file.fail("no variable '" + variable + "' (the file has: " + variable_list(nc) + ")");
  file.check(nc_inq_varndims(nc, var, &ndims), variable);
  return {var, ndims};
}

LonLatGrid read_grid_here(const std::filesystem::path& path, const std::string& variable,
                          std::size_t time_index) {
  const NcFile file(path);
  const int nc = file.id();
  const auto [var, ndims] = find_variable(file, variable);
  if (ndims < 2 || ndims > 3)
    file.fail("'" + variable + "' has " + std::to_string(ndims) +
              " dimensions; expected (latitude, longitude) or (time, latitude, longitude)");
  int dims[3] = {};
  file.check(nc_inq_vardimid(nc, var, dims), variable);
  std::size_t len[3] = {1, 1, 1};
  for (int d = 0; d < ndims; ++d) file.check(nc_inq_dimlen(nc, dims[d], &len[d]), variable);
  LonLatGrid g;
  g.name = variable;
  const std::size_t ny = len[ndims - 2], nx = len[ndims - 1];
  if (nx < 2 || ny < 2) file.fail("'" + variable + "' is not a grid (fewer than 2 x 2 points)");
  g.time_steps = ndims == 3 ? len[0] : 1;
  if (time_index >= g.time_steps)
    file.fail("time index " + std::to_string(time_index) + " is out of range for '" + variable +
              "' (" + std::to_string(g.time_steps) + " time step" + (g.time_steps == 1 ? "" : "s") +
              ", counted from 0)");
  // A header can declare any size: refuse one that cannot fit before
  // allocating the slice and its coordinates.
  try {
    check_memory(static_cast<double>(nx) * static_cast<double>(ny) * sizeof(float) +
                     (static_cast<double>(nx) + static_cast<double>(ny)) * sizeof(double),
                 "'" + variable + "' (" + std::to_string(ny) + " x " + std::to_string(nx) + ")");
  } catch (const InputError& e) {
    file.fail(e.what());
  }
  g.lat = coordinates(file, dims[ndims - 2], ny);
  g.lon = coordinates(file, dims[ndims - 1], nx);
  if (!std::is_sorted(g.lon.begin(), g.lon.end()) || g.lon.front() == g.lon.back())
    file.fail("the longitudes of '" + variable + "' do not increase");
  std::size_t start[3] = {0, 0, 0}, count[3] = {1, ny, nx};
  if (ndims == 3) start[0] = time_index;
  g.values.resize(nx * ny);
  file.check(nc_get_vara_float(nc, var, ndims == 3 ? start : start + 1,
                               ndims == 3 ? count : count + 1, g.values.data()),
             "reading '" + variable + "'");
  double fill = 0, missing = 0, scale = 1, offset = 0;
  const bool has_fill = attribute(nc, var, "_FillValue", fill);
  const bool has_missing = attribute(nc, var, "missing_value", missing);
  attribute(nc, var, "scale_factor", scale);
  attribute(nc, var, "add_offset", offset);
  const auto same = [](float v, double m) {
    return std::abs(static_cast<double>(v) - m) <= 1e-6 * std::max(1.0, std::abs(m));
  };
  for (float& v : g.values) {
    if ((has_fill && same(v, fill)) || (has_missing && same(v, missing)) || !std::isfinite(v))
      v = std::numeric_limits<float>::quiet_NaN();
    else
      v = static_cast<float>(v * scale + offset);
  }
  g.units = text_attribute(nc, var, "units");
  return g;
}

TimeAxis time_axis_here(const std::filesystem::path& path, const std::string& variable) {
  const NcFile file(path);
  const int nc = file.id();
  const auto [var, ndims] = find_variable(file, variable);
  TimeAxis axis;
  if (ndims != 3) return axis;
  int dims[3] = {};
  file.check(nc_inq_vardimid(nc, var, dims), variable);
  char name[NC_MAX_NAME + 1] = {};
  std::size_t n = 0;
  file.check(nc_inq_dimname(nc, dims[0], name), variable);
  file.check(nc_inq_dimlen(nc, dims[0], &n), variable);
  int coordinate = -1, coordinate_dims = 0, coordinate_dim = -1;
  if (nc_inq_varid(nc, name, &coordinate) != NC_NOERR ||
      nc_inq_varndims(nc, coordinate, &coordinate_dims) != NC_NOERR || coordinate_dims != 1 ||
      nc_inq_vardimid(nc, coordinate, &coordinate_dim) != NC_NOERR || coordinate_dim != dims[0])
    return axis;  // no coordinate variable: steps without times
  try {
    check_memory(static_cast<double>(n) * sizeof(double),
                 std::string("the time axis '") + name + "' (" + std::to_string(n) + " values)");
  } catch (const InputError& e) {
    file.fail(e.what());
  }
  axis.values.resize(n);
  file.check(nc_get_var_double(nc, coordinate, axis.values.data()),
             std::string("reading '") + name + "'");
  axis.units = text_attribute(nc, coordinate, "units");
  axis.calendar = text_attribute(nc, coordinate, "calendar");
  return axis;
}

}  // namespace

bool netcdf_built_in() {
  return true;
}

void set_lonlat_reader(LonLatReader /*reader*/) {}  // netCDF-C reads every file here

std::vector<std::string> netcdf_variables(const std::filesystem::path& path) {
  const IsolatedBytes bytes =
      read_isolated(path, [&](ByteWriter& out) { out.put(variable_names(NcFile(path).id())); });
  ByteReader in(bytes.view(), path.string());
  return in.get_strings();
}

LonLatGrid read_lonlat_grid(const std::filesystem::path& path, const std::string& variable,
                            std::size_t time_index) {
  const IsolatedBytes bytes = read_isolated(path, [&](ByteWriter& out) {
    const LonLatGrid g = read_grid_here(path, variable, time_index);
    out.put(g.name);
    out.put(g.units);
    out.put(g.lon);
    out.put(g.lat);
    out.put(g.values);
    out.put<std::uint64_t>(g.time_steps);
  });
  ByteReader in(bytes.view(), path.string());
  LonLatGrid g;
  g.name = in.get_string();
  g.units = in.get_string();
  g.lon = in.get_vector<double>();
  g.lat = in.get_vector<double>();
  g.values = in.get_vector<float>();
  g.time_steps = static_cast<std::size_t>(in.get<std::uint64_t>());
  return g;
}

TimeAxis netcdf_time_axis(const std::filesystem::path& path, const std::string& variable) {
  const IsolatedBytes bytes = read_isolated(path, [&](ByteWriter& out) {
    const TimeAxis axis = time_axis_here(path, variable);
    out.put(axis.values);
    out.put(axis.units);
    out.put(axis.calendar);
  });
  ByteReader in(bytes.view(), path.string());
  TimeAxis axis;
  axis.values = in.get_vector<double>();
  axis.units = in.get_string();
  axis.calendar = in.get_string();
  return axis;
}

}  // namespace ibfvs
