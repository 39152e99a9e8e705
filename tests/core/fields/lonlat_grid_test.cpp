// Gridded data on the globe: synthetic netCDF files written here with
// libnetcdf, and the real monthly winds when fetched.

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <netcdf.h>
#include <glm/geometric.hpp>

#include "helpers.h"
#include "ibfvs/core/fields/lonlat_grid.h"
#include "ibfvs/core/fields/vector_field.h"
#include "ibfvs/core/support/error.h"

namespace ibfvs {
namespace {

constexpr float kMissing = -99.9f;

// A file like monthly_navy_winds.cdf: 2.5 degree grid, lon 0..357.5, lat
// -90..90, `steps` time steps of U (eastward) and V (northward). U is
// u(t) everywhere, V zero; the cell at (lon 100, lat 20) is missing.
void write_winds(const std::filesystem::path& path, int steps, bool v_on_other_grid = false) {
  int nc = 0, dx = 0, dy = 0, dt = 0, dy2 = 0, vx = 0, vy = 0, vu = 0, vv = 0;
  ASSERT_EQ(nc_create(path.c_str(), NC_CLOBBER, &nc), NC_NOERR);
  nc_def_dim(nc, "LON", 144, &dx);
  nc_def_dim(nc, "LAT", 73, &dy);
  nc_def_dim(nc, "TIME", NC_UNLIMITED, &dt);
  nc_def_dim(nc, "LAT2", 37, &dy2);
  nc_def_var(nc, "LON", NC_DOUBLE, 1, &dx, &vx);
  nc_def_var(nc, "LAT", NC_DOUBLE, 1, &dy, &vy);
  const int du[3] = {dt, dy, dx}, dv[3] = {dt, v_on_other_grid ? dy2 : dy, dx};
  nc_def_var(nc, "U", NC_FLOAT, 3, du, &vu);
  nc_def_var(nc, "V", NC_FLOAT, 3, dv, &vv);
  for (const int v : {vu, vv}) {
    nc_put_att_float(nc, v, "_FillValue", NC_FLOAT, 1, &kMissing);
    nc_put_att_float(nc, v, "missing_value", NC_FLOAT, 1, &kMissing);
    nc_put_att_text(nc, v, "units", 3, "M/S");
  }
  nc_enddef(nc);
  std::vector<double> lon(144), lat(73);
  for (int i = 0; i < 144; ++i) lon[i] = 2.5 * i;
  for (int j = 0; j < 73; ++j) lat[j] = -90 + 2.5 * j;
  nc_put_var_double(nc, vx, lon.data());
  nc_put_var_double(nc, vy, lat.data());
  for (int t = 0; t < steps; ++t) {
    std::vector<float> u(144 * 73, 5.0f + t), v(144 * 73, 0.0f);
    u[44 * 144 + 40] = kMissing;  // lat 20, lon 100
    const std::size_t start[3] = {static_cast<std::size_t>(t), 0, 0};
    const std::size_t cu[3] = {1, 73, 144}, cv[3] = {1, v_on_other_grid ? 37u : 73u, 144};
    nc_put_vara_float(nc, vu, start, cu, u.data());
    nc_put_vara_float(nc, vv, start, cv, v.data());
  }
  nc_close(nc);
}

// `read` of `file` throws one InputError line that begins with the file's
// name and says `needle`.
template <class Read>
void expect_one_line(const std::filesystem::path& file, const std::string& needle, Read read) {
  try {
    read();
    ADD_FAILURE() << "no error for " << file;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(file.string() + ": ", 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find(needle), std::string::npos) << what;
  }
}

TEST(LonLatGrid, EastwardWindRunsAlongTheParallels) {
  test::TempDir dir;
  write_winds(dir / "w.nc", 3);
  const LonLatGrid u = read_lonlat_grid(dir / "w.nc", "U", 2);
  EXPECT_EQ(u.time_steps, 3u);
  EXPECT_EQ(u.units, "M/S");
  EXPECT_FLOAT_EQ(u.sample(10, 10), 7.0f);
  EXPECT_FLOAT_EQ(u.sample(358.9, 10), 7.0f);  // between the last and first column
  EXPECT_FLOAT_EQ(u.sample(-1.0, 10), 7.0f);   // negative longitudes wrap
  EXPECT_TRUE(std::isnan(u.sample(100, 20)));  // missing stays missing
  const TriMesh globe = make_globe(4);
  std::vector<float> valid;
  const auto v = lonlat_vectors(globe, u, read_lonlat_grid(dir / "w.nc", "V", 2), &valid);
  std::size_t missing = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    double lon = 0, lat = 0;
    to_lonlat(globe.positions[i], lon, lat);
    if (!valid[i]) {
      ++missing;
      EXPECT_EQ(v[i], glm::vec3(0));
      EXPECT_NEAR(lon, 100.0, 5.1);
      continue;
    }
    if (std::abs(lat) > 85) continue;
    const double l = lon * 3.14159265358979 / 180.0;
    const glm::vec3 east(std::cos(l), 0, -std::sin(l));
    EXPECT_NEAR(glm::dot(v[i], east), 7.0f, 1e-3f);
    EXPECT_NEAR(glm::dot(v[i], globe.normals[i]), 0.0f, 1e-4f);  // tangent
    EXPECT_NEAR(glm::length(v[i]), 7.0f, 1e-3f);                 // no northward part
  }
  EXPECT_GT(missing, 0u);
  EXPECT_LT(missing, 20u);
  // Through the field spec, as --field wind:FILE:U:V uses it.
  FieldSpec spec = FieldSpec::parse("wind:" + (dir / "w.nc").string() + ":U:V");
  spec.time = 1;
  const auto f = evaluate_field(globe, spec, TangentMode::Project);
  EXPECT_NEAR(glm::length(f[0]) + glm::length(f[1]), 12.0f, 0.1f);
}

TEST(LonLatGrid, BadFilesAndNamesAreClearErrors) {
  test::TempDir dir;
  write_winds(dir / "w.nc", 2);
  const auto expect = [&](auto&& call, const std::string& needle) {
    try {
      call();
      FAIL() << "no error for " << needle;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect([&] { read_lonlat_grid(dir / "w.nc", "UWND"); },
         "no variable 'UWND' (the file has: LON, LAT, U, V)");
  expect([&] { read_lonlat_grid(dir / "w.nc", "U", 2); },
         "time index 2 is out of range for 'U' (2 time steps");
  expect([&] { read_lonlat_grid(dir / "w.nc", "LON"); }, "has 1 dimensions");
  expect([&] { read_lonlat_grid(dir / "none.nc", "U"); }, "none.nc: no such file");
  expect([&] { read_lonlat_grid(test::write_file(dir / "t.nc", "not netcdf"), "U"); },
         "t.nc: not a readable netCDF file");
  write_winds(dir / "odd.nc", 1, true);
  const TriMesh globe = make_globe(2);
  expect(
      [&] {
        lonlat_vectors(globe, read_lonlat_grid(dir / "odd.nc", "U"),
                       read_lonlat_grid(dir / "odd.nc", "V"));
      },
      "mismatched dimensions");
  expect([&] { FieldSpec::parse("wind:"); }, "empty file or variable name in 'wind:'");
}

// A classic netCDF header written byte by byte (big-endian words).
struct Header {
  std::string bytes;
  explicit Header(char version) : bytes(std::string("CDF") + version) {}
  Header& word(std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>((v >> shift) & 0xFF);
    return *this;
  }
  Header& name(const std::string& n) {
    word(static_cast<std::uint32_t>(n.size()));
    bytes += n + std::string((4 - n.size() % 4) % 4, '\0');
    return *this;
  }
};

// Fuzzing found netCDF-C allocating what a header declares (tens of GiB for
// a few hundred bytes) and spinning for minutes; and a file cut short read
// as zeros. Nothing of ours walks the header first: netCDF-C reads in a
// child (support/isolation.h), where such a file is one error line naming
// it, and from memory, where reading past the end is an error, not zeros.
TEST(LonLatGrid, MalformedAndCutShortFilesAreCleanErrors) {
  test::TempDir dir;
  const auto expect = [&](const std::filesystem::path& file, const std::string& needle,
                          const std::string& variable = "U", std::size_t time = 0) {
    expect_one_line(file, needle, [&] { (void)read_lonlat_grid(file, variable, time); });
  };
  // Whole files of the three classic versions read; one byte less is cut short.
  for (const int mode : {0, NC_64BIT_OFFSET, NC_64BIT_DATA}) {
    int nc = 0, d[2] = {}, v = 0;
    const auto path = dir / ("v" + std::to_string(mode) + ".nc");
    ASSERT_EQ(nc_create(path.c_str(), NC_CLOBBER | mode, &nc), NC_NOERR);
    nc_def_dim(nc, "Y", 2, &d[0]);
    nc_def_dim(nc, "X", 4, &d[1]);
    nc_def_var(nc, "W", NC_DOUBLE, 2, d, &v);
    nc_enddef(nc);
    const std::vector<double> w{0, 1, 2, 3, 4, 5, 6, 7};
    nc_put_var_double(nc, v, w.data());
    nc_close(nc);
    const std::string bytes = test::read_file(path);
    EXPECT_EQ(read_lonlat_grid(path, "W").values[7], 7.0f) << mode;
    test::write_file(path, bytes.substr(0, bytes.size() - 1));
    expect(path, "reading 'W': the file ends before its data (cut short)", "W");
  }
  write_winds(dir / "w.nc", 2);
  const std::string whole = test::read_file(dir / "w.nc");
  EXPECT_EQ(read_lonlat_grid(dir / "w.nc", "U", 1).time_steps, 2u);
  test::write_file(dir / "cut.nc", whole.substr(0, whole.size() - 100));
  expect(dir / "cut.nc", "the file ends before its data (cut short)", "V", 1);
  // Headers declaring what no file of their size could hold: each one line
  // naming the file, whatever netCDF-C makes of it.
  expect(test::write_file(dir / "dims.nc", Header('\1').word(0).word(0x0A).word(0x7FFFFFFF).bytes),
         "");
  expect(test::write_file(dir / "att.nc", Header('\2')
                                              .word(0)
                                              .word(0)
                                              .word(0)
                                              .word(0x0C)
                                              .word(1)
                                              .name("title")
                                              .word(2)
                                              .word(0x7FFFFFF0)
                                              .bytes),
         "");
  Header rank('\1');
  rank.word(0).word(0x0A).word(1).name("x").word(4).word(0).word(0).word(0x0B).word(1).name("U");
  expect(test::write_file(dir / "rank.nc", rank.word(2000).bytes + std::string(64, '\0')), "");
  Header id('\1');
  id.word(0).word(0x0A).word(1).name("x").word(4).word(0).word(0).word(0x0B).word(1).name("U");
  expect(test::write_file(dir / "id.nc", id.word(1).word(5).bytes + std::string(64, '\0')), "");
  // Names are the file's bytes: the message stays one line.
  expect(test::write_file(
             dir / "name.nc",
             Header('\1').word(0).word(0).word(0).word(0x0C).word(1).name("a\nb").word(99).bytes +
                 std::string(64, '\0')),
         "");
  expect(test::write_file(dir / "version.nc", Header('\3').word(0).bytes), "");
  expect(test::write_file(dir / "short.nc", Header('\1').word(0).word(0x0A).bytes), "");
}

TEST(LonLatGrid, GlobeIsAUnitGeodesicSphere) {
  const TriMesh g = make_globe(3);
  EXPECT_EQ(g.triangle_count(), 20u * 64);
  for (std::size_t i = 0; i < g.vertex_count(); ++i) {
    EXPECT_NEAR(glm::length(g.positions[i]), 1.0f, 1e-5f);
    EXPECT_EQ(g.positions[i], g.normals[i]);
  }
  double lon = 0, lat = 0;
  to_lonlat({0, 1, 0}, lon, lat);
  EXPECT_NEAR(lat, 90.0, 1e-9);
  to_lonlat({1, 0, 0}, lon, lat);
  EXPECT_NEAR(lon, 90.0, 1e-9);  // east of longitude 0 (+Z)
  EXPECT_THROW(make_globe(9), InputError);
}

TEST(LonLatGrid, TheTimeAxisIsTheTimeDimensionsCoordinates) {
  test::TempDir dir;
  write_winds(dir / "w.nc", 2);  // no TIME variable: steps without times
  EXPECT_TRUE(netcdf_time_axis(dir / "w.nc", "U").values.empty());
  EXPECT_TRUE(netcdf_time_axis(dir / "w.nc", "LON").values.empty());  // no time dimension
  EXPECT_THROW(netcdf_time_axis(dir / "w.nc", "W"), InputError);
  // A model's days on a 365-day calendar.
  int nc = 0, dt = 0, dy = 0, dx = 0, vt = 0, vu = 0;
  ASSERT_EQ(nc_create((dir / "t.nc").c_str(), NC_CLOBBER | NC_NETCDF4, &nc), NC_NOERR);
  nc_def_dim(nc, "time", 3, &dt);
  nc_def_dim(nc, "lat", 2, &dy);
  nc_def_dim(nc, "lon", 2, &dx);
  nc_def_var(nc, "time", NC_DOUBLE, 1, &dt, &vt);
  const int du[3] = {dt, dy, dx};
  nc_def_var(nc, "u", NC_FLOAT, 3, du, &vu);
  nc_put_att_text(nc, vt, "units", 21, "days since 1999-12-31");
  nc_put_att_text(nc, vt, "calendar", 6, "noleap");
  nc_enddef(nc);
  const double days[3] = {0, 60, 365};
  nc_put_var_double(nc, vt, days);
  nc_close(nc);
  const TimeAxis axis = netcdf_time_axis(dir / "t.nc", "u");
  EXPECT_EQ(axis.values, (std::vector<double>{0, 60, 365}));
  EXPECT_EQ(axis.units, "days since 1999-12-31");
  EXPECT_EQ(axis.calendar, "noleap");
  EXPECT_EQ(time_labels(axis, 0, 2),
            (std::vector<std::string>{"1999-12-31", "2000-03-01", "2000-12-31"}));
}

TEST(LonLatGrid, ABadFilesTimeAxisIsOneErrorNamingTheFile) {
  test::TempDir dir;
  const auto expect = [&](const std::filesystem::path& file, const std::string& needle) {
    expect_one_line(file, needle, [&] { (void)netcdf_time_axis(file, "U"); });
  };
  // A classic file whose records end with the time coordinate's value: one
  // byte less cuts the last time short.
  int nc = 0, dt = 0, dy = 0, dx = 0, vu = 0, vt = 0;
  const auto path = dir / "t.nc";
  ASSERT_EQ(nc_create(path.c_str(), NC_CLOBBER, &nc), NC_NOERR);
  nc_def_dim(nc, "TIME", NC_UNLIMITED, &dt);
  nc_def_dim(nc, "Y", 2, &dy);
  nc_def_dim(nc, "X", 2, &dx);
  const int du[3] = {dt, dy, dx};
  nc_def_var(nc, "U", NC_FLOAT, 3, du, &vu);
  nc_def_var(nc, "TIME", NC_DOUBLE, 1, &dt, &vt);
  nc_put_att_text(nc, vt, "units", 21, "days since 2000-01-01");
  nc_enddef(nc);
  for (std::size_t k = 0; k < 3; ++k) {
    const float u[4] = {1, 2, 3, 4};
    const double t = static_cast<double>(k);
    const std::size_t start[3] = {k, 0, 0}, count[3] = {1, 2, 2};
    nc_put_vara_float(nc, vu, start, count, u);
    nc_put_var1_double(nc, vt, &k, &t);
  }
  nc_close(nc);
  EXPECT_EQ(netcdf_time_axis(path, "U").values, (std::vector<double>{0, 1, 2}));
  const std::string bytes = test::read_file(path);
  test::write_file(path, bytes.substr(0, bytes.size() - 1));
  expect(path, "reading 'TIME': the file ends before its data (cut short)");
  test::write_file(dir / "junk.nc", "CDF\x01 but not really");
  expect(dir / "junk.nc", "not a readable netCDF file");
  expect(dir / "none.nc", "no such file");
}

TEST(LonLatGrid, RealMonthlyWindsAreDatedByTheirTimeAxis) {
  const std::filesystem::path path =
      std::filesystem::path(IBFVS_TEST_DATA_DIR) / "earth/monthly_navy_winds.cdf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "fetched data missing: " << path;
  const TimeAxis axis = netcdf_time_axis(path, "UWND");
  ASSERT_EQ(axis.values.size(), 132u);
  EXPECT_EQ(axis.units, "hour since 1980-01-14 14:00:00");
  const std::vector<std::string> months = time_labels(axis, 0, 131);
  EXPECT_EQ(months.front(), "1982-01-16 20:00");
  EXPECT_EQ(months[6].substr(0, 7), "1982-07");
  EXPECT_EQ(months.back(), "1992-12-17 03:30");
  for (std::size_t k = 0; k < months.size(); ++k)  // one a month, every month
    EXPECT_EQ(std::stoi(months[k].substr(5, 2)), static_cast<int>(k % 12) + 1) << months[k];
}

TEST(LonLatGrid, RealMonthlyWindsHaveTheWesterlies) {
  const std::filesystem::path path =
      std::filesystem::path(IBFVS_TEST_DATA_DIR) / "earth/monthly_navy_winds.cdf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "fetched data missing: " << path;
  const LonLatGrid u = read_lonlat_grid(path, "UWND", 0);
  EXPECT_EQ(u.time_steps, 132u);
  EXPECT_EQ(u.lon.size(), 144u);
  EXPECT_EQ(u.lat.size(), 73u);
  // The roaring forties and fifties blow from the west: u > 0 around -50.
  double sum = 0, trades = 0;
  int n = 0, m = 0;
  float lo = 1e9f, hi = -1e9f;
  for (double lon = 0; lon < 360; lon += 5) {
    const float v = u.sample(lon, -50);
    if (std::isfinite(v)) sum += v, ++n;
    const float t = u.sample(lon, 12);  // the north-east trades over the oceans: u < 0
    if (std::isfinite(t)) trades += t, ++m;
  }
  for (const float v : u.values)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  std::printf("January 1982: mean u at -50 %.1f m/s, at 12N %.1f m/s, range %.1f..%.1f\n", sum / n,
              trades / m, lo, hi);
  EXPECT_GT(sum / n, 5.0);
  EXPECT_LT(trades / m, -2.0);
  EXPECT_GT(lo, -40.0f);
  EXPECT_LT(hi, 40.0f);
}

}  // namespace
}  // namespace ibfvs
