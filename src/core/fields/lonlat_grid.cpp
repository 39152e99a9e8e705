#include "ibfvs/core/fields/lonlat_grid.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <functional>
#include <numbers>

#include <fcntl.h>
#include <netcdf.h>
#include <netcdf_mem.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <glm/geometric.hpp>

#include "ibfvs/core/mesh/procedural.h"
#include "ibfvs/core/mesh/subdivision.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/isolation.h"
#include "ibfvs/core/support/limits.h"

namespace ibfvs {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

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

// Index i and weight t with x between axis[i] and axis[i + 1] (axis monotonic).
void bracket(const std::vector<double>& axis, double x, std::size_t& i, double& t) {
  const bool up = axis.back() >= axis.front();
  const auto it = up ? std::upper_bound(axis.begin(), axis.end(), x)
                     : std::upper_bound(axis.begin(), axis.end(), x, std::greater<>());
  const std::size_t k = static_cast<std::size_t>(it - axis.begin());
  i = std::clamp<std::size_t>(k == 0 ? 0 : k - 1, 0, axis.size() - 2);
  t = std::clamp((x - axis[i]) / (axis[i + 1] - axis[i]), 0.0, 1.0);
}

}  // namespace

float LonLatGrid::sample(double lon_deg, double lat_deg) const {
  const std::size_t nx = lon.size(), ny = lat.size();
  if (nx < 2 || ny < 2) return std::numeric_limits<float>::quiet_NaN();
  // Longitude: bring into [lon0, lon0 + 360) and wrap between the last and
  // first column when the grid covers the globe.
  const double lon0 = lon.front();
  double x = std::fmod(lon_deg - lon0, 360.0);
  if (x < 0) x += 360.0;
  x += lon0;
  const double step = (lon.back() - lon.front()) / static_cast<double>(nx - 1);
  std::size_t i0 = 0, i1 = 0;
  double tx = 0;
  if (x > lon.back()) {
    const double gap = lon0 + 360.0 - lon.back();
    if (gap > 1.5 * step) return std::numeric_limits<float>::quiet_NaN();  // not global
    i0 = nx - 1, i1 = 0;
    tx = (x - lon.back()) / gap;
  } else {
    bracket(lon, x, i0, tx);
    i1 = i0 + 1;
  }
  std::size_t j0 = 0;
  double ty = 0;
  bracket(lat, lat_deg, j0, ty);
  const auto at = [&](std::size_t j, std::size_t i) {
    return static_cast<double>(values[j * nx + i]);
  };
  const double v = (1 - ty) * ((1 - tx) * at(j0, i0) + tx * at(j0, i1)) +
                   ty * ((1 - tx) * at(j0 + 1, i0) + tx * at(j0 + 1, i1));
  return static_cast<float>(v);  // NaN propagates from any missing neighbour
}

namespace {

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

LonLatGrid read_grid_here(const std::filesystem::path& path, const std::string& variable,
                          std::size_t time_index) {
  const NcFile file(path);
  const int nc = file.id();
  int var = -1;
  if (nc_inq_varid(nc, variable.c_str(), &var) != NC_NOERR)
    file.fail("no variable '" + variable + "' (the file has: " + variable_list(nc) + ")");
  int ndims = 0;
  file.check(nc_inq_varndims(nc, var, &ndims), variable);
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
  std::size_t units_len = 0;
  if (nc_inq_attlen(nc, var, "units", &units_len) == NC_NOERR) {
    g.units.resize(units_len);
    nc_get_att_text(nc, var, "units", g.units.data());
  }
  return g;
}

}  // namespace

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

TriMesh make_globe(int level) {
  if (level < 0 || level > 8) throw InputError("globe: the level must be between 0 and 8");
  TriMesh m = loop_subdivide(make_icosahedron(1.0f), level);
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    m.normals[i] = glm::normalize(m.positions[i]);
    m.positions[i] = m.normals[i];
  }
  return m;
}

void to_lonlat(const glm::vec3& p, double& lon_deg, double& lat_deg) {
  const glm::dvec3 d = glm::normalize(glm::dvec3(p));
  lat_deg = std::asin(std::clamp(d.y, -1.0, 1.0)) / kDeg;
  lon_deg = std::atan2(d.x, d.z) / kDeg;
}

std::vector<glm::vec3> lonlat_vectors(const TriMesh& globe, const LonLatGrid& east,
                                      const LonLatGrid& north, std::vector<float>* valid) {
  if (east.lon != north.lon || east.lat != north.lat)
    throw InputError("'" + east.name + "' and '" + north.name +
                     "' are on different grids (mismatched dimensions)");
  std::vector<glm::vec3> out(globe.vertex_count(), glm::vec3(0.0f));
  if (valid) valid->assign(out.size(), 1.0f);
  for (std::size_t i = 0; i < out.size(); ++i) {
    double lon = 0, lat = 0;
    to_lonlat(globe.positions[i], lon, lat);
    const float u = east.sample(lon, lat), v = north.sample(lon, lat);
    if (!std::isfinite(u) || !std::isfinite(v)) {
      if (valid) (*valid)[i] = 0.0f;
      continue;
    }
    const double l = lon * kDeg, p = lat * kDeg;
    const glm::dvec3 e(std::cos(l), 0.0, -std::sin(l));
    const glm::dvec3 n(-std::sin(p) * std::sin(l), std::cos(p), -std::sin(p) * std::cos(l));
    out[i] = glm::vec3(static_cast<double>(u) * e + static_cast<double>(v) * n);
  }
  return out;
}

std::vector<float> lonlat_scalars(const TriMesh& globe, const LonLatGrid& grid) {
  std::vector<float> out(globe.vertex_count());
  for (std::size_t i = 0; i < out.size(); ++i) {
    double lon = 0, lat = 0;
    to_lonlat(globe.positions[i], lon, lat);
    out[i] = grid.sample(lon, lat);
  }
  return out;
}

}  // namespace ibfvs
