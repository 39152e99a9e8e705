/* Writes the netCDF fuzzer's seeds (committed in fuzz/corpus/netcdf_fuzzer):
 * small lon/lat grids in the classic, 64-bit offset and netCDF-4 formats,
 * with a time dimension, coordinate variables, missing values, packing
 * (scale_factor, add_offset) and units. Build: cc make_netcdf_seeds.c -lnetcdf */
#include <netcdf.h>
#include <stdio.h>
#include <stdlib.h>

#define CHECK(x) do { int s_ = (x); if (s_ != NC_NOERR) { fprintf(stderr, "%s\n", nc_strerror(s_)); exit(1); } } while (0)

static void write_grid(const char* path, int mode, int packed) {
  int nc, dt, dy, dx, vt, vy, vx, vu, vv;
  CHECK(nc_create(path, mode, &nc));
  CHECK(nc_def_dim(nc, "TIME", 2, &dt));
  CHECK(nc_def_dim(nc, "LAT", 4, &dy));
  CHECK(nc_def_dim(nc, "LON", 8, &dx));
  CHECK(nc_def_var(nc, "TIME", NC_DOUBLE, 1, &dt, &vt));
  CHECK(nc_def_var(nc, "LAT", NC_FLOAT, 1, &dy, &vy));
  CHECK(nc_def_var(nc, "LON", NC_DOUBLE, 1, &dx, &vx));
  int dims[3] = {dt, dy, dx};
  CHECK(nc_def_var(nc, "UWND", packed ? NC_SHORT : NC_FLOAT, 3, dims, &vu));
  CHECK(nc_def_var(nc, "VWND", NC_FLOAT, 2, dims + 1, &vv));
  CHECK(nc_put_att_text(nc, vu, "units", 3, "m/s"));
  if (packed) {
    short fill = -32767;
    double scale = 0.01, offset = 1.0;
    CHECK(nc_put_att_short(nc, vu, "_FillValue", NC_SHORT, 1, &fill));
    CHECK(nc_put_att_double(nc, vu, "scale_factor", NC_DOUBLE, 1, &scale));
    CHECK(nc_put_att_double(nc, vu, "add_offset", NC_DOUBLE, 1, &offset));
  } else {
    float missing = -99.0f;
    CHECK(nc_put_att_float(nc, vu, "missing_value", NC_FLOAT, 1, &missing));
  }
  CHECK(nc_enddef(nc));
  double t[2] = {0, 30}, lon[8];
  float lat[4] = {60, 20, -20, -60};
  for (int i = 0; i < 8; ++i) lon[i] = 45.0 * i;
  CHECK(nc_put_var_double(nc, vt, t));
  CHECK(nc_put_var_float(nc, vy, lat));
  CHECK(nc_put_var_double(nc, vx, lon));
  if (packed) {
    short u[64];
    for (int i = 0; i < 64; ++i) u[i] = (short)(i == 5 ? -32767 : i * 10);
    CHECK(nc_put_var_short(nc, vu, u));
  } else {
    float u[64];
    for (int i = 0; i < 64; ++i) u[i] = i == 7 ? -99.0f : (float)i;
    CHECK(nc_put_var_float(nc, vu, u));
  }
  float v[32];
  for (int i = 0; i < 32; ++i) v[i] = (float)(i % 5);
  CHECK(nc_put_var_float(nc, vv, v));
  CHECK(nc_close(nc));
}

int main(void) {
  write_grid("classic.nc", NC_CLOBBER, 0);
  write_grid("offset64.nc", NC_CLOBBER | NC_64BIT_OFFSET, 1);
  write_grid("netcdf4.nc", NC_CLOBBER | NC_NETCDF4, 1);
  return 0;
}
