"""What the pip package leaves to Python's own packages (docs/python.md,
"The wheel"): its build has neither FFmpeg's libraries nor netCDF-C.

- Video goes through the ffmpeg program: IBFVS_FFMPEG where it is set, else
  imageio-ffmpeg's (the wheel PyVista's open_movie uses too), else `ffmpeg`
  on PATH.
- netCDF files are read with xarray (its netCDF4, h5netcdf or scipy engine),
  as the Debian build reads them with netCDF-C: the last two dimensions
  latitude and longitude, an optional leading time, missing values NaN,
  scale_factor and add_offset applied; the time axis's values, units and
  calendar as the file states them (the library makes them dates).
The Debian build (which has both) uses neither.
"""

from __future__ import annotations

import atexit
import os

import numpy as np

from . import _ibfvs

_NETCDF_HELP = "reading netCDF in the pip package needs xarray and netCDF4: pip install 'ibfvs[netcdf]'"


def find_ffmpeg() -> None:
    """Names imageio-ffmpeg's program in IBFVS_FFMPEG where this build has no
    libav and nothing names one yet (the writer then looks on PATH)."""
    if _ibfvs.has_libav or os.environ.get("IBFVS_FFMPEG"):
        return
    try:
        import imageio_ffmpeg
    except ImportError:
        return
    try:
        os.environ["IBFVS_FFMPEG"] = imageio_ffmpeg.get_ffmpeg_exe()
    except RuntimeError:  # its wheel without a program for this platform
        return


def _open(path):
    try:
        import xarray
    except ImportError:
        raise ImportError(_NETCDF_HELP) from None
    try:
        return xarray.open_dataset(path, mask_and_scale=True, decode_times=False)
    except (ValueError, OSError) as e:  # no engine for it, or not a netCDF file
        raise ValueError(f"not a readable netCDF file ({e}); {_NETCDF_HELP}") from None


def netcdf_variables(path):
    with _open(path) as ds:
        return [str(name) for name in ds.variables]


def _axis(ds, dim, n):
    """The coordinate variable of a dimension, else 0 .. n-1 (as netCDF-C's reader)."""
    if dim in ds.variables and ds[dim].ndim == 1 and ds[dim].size == n:
        return np.asarray(ds[dim].values, dtype=np.float64)
    return np.arange(n, dtype=np.float64)


def netcdf_grid(path, variable, time_index):
    """(lon, lat, values (lat, lon) float32 with NaN where missing, units, time steps)."""
    with _open(path) as ds:
        if variable not in ds.variables:
            raise ValueError(f"no variable '{variable}' (the file has: {', '.join(map(str, ds.variables))})")
        v = ds[variable]
        if v.ndim not in (2, 3):
            raise ValueError(f"'{variable}' has {v.ndim} dimensions; expected (latitude, longitude) "
                             "or (time, latitude, longitude)")
        steps = v.shape[0] if v.ndim == 3 else 1
        if time_index >= steps:
            raise ValueError(f"time index {time_index} is out of range for '{variable}' "
                             f"({steps} time step{'' if steps == 1 else 's'}, counted from 0)")
        ny, nx = v.shape[-2:]
        grid = v[time_index] if v.ndim == 3 else v
        values = np.asarray(grid.values, dtype=np.float32)
        return (_axis(ds, v.dims[-1], nx), _axis(ds, v.dims[-2], ny), values,
                str(v.attrs.get("units", "")), steps)


def netcdf_time_axis(path, variable):
    """(values, units, calendar) of the coordinate variable of the variable's
    leading (time) dimension, as the file states them; ([], "", "") where
    there is none (a 2-D variable, a time dimension without coordinates)."""
    with _open(path) as ds:
        if variable not in ds.variables:
            raise ValueError(f"no variable '{variable}' (the file has: {', '.join(map(str, ds.variables))})")
        v = ds[variable]
        if v.ndim != 3:
            return [], "", ""
        t = v.dims[0]
        if t not in ds.variables or ds[t].ndim != 1 or ds[t].dims[0] != t:
            return [], "", ""
        axis = ds[t]
        return (np.asarray(axis.values, dtype=np.float64).tolist(), str(axis.attrs.get("units", "")),
                str(axis.attrs.get("calendar", "")))


def install() -> None:
    """Gives a build without netCDF-C the xarray reader, taken back at exit
    while Python still runs (the library holds it past the interpreter)."""
    if not _ibfvs.has_netcdf:
        _ibfvs.set_netcdf_reader(netcdf_variables, netcdf_grid, netcdf_time_axis)
        atexit.register(_ibfvs.set_netcdf_reader, None, None, None)
