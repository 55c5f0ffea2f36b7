"""Dataset I/O: the one place where rockstudy writes and reads files.

Writes are atomic (a temporary file in the same folder, then ``os.replace``), so an
interrupted run never leaves a half-written netCDF file behind.
"""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np
import xarray as xr


def netcdf_attr(value):
    """A value netCDF can hold as an attribute (bools → int, None → "none", dicts → str)."""
    if isinstance(value, (bool, np.bool_)):
        return int(value)
    if value is None:
        return "none"
    if isinstance(value, (dict, list, tuple)) and not all(isinstance(v, (int, float)) for v in value):
        return str(value)
    return value


def clean_attrs(attrs: dict) -> dict:
    return {k: netcdf_attr(v) for k, v in attrs.items()}


def write_netcdf(ds: xr.Dataset, path, *, compress: bool = True) -> Path:
    """Write ``ds`` to ``path`` atomically, with zlib compression of the data variables."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    ds = ds.copy()
    ds.attrs = clean_attrs(ds.attrs)
    for name in list(ds.variables):
        ds[name].attrs = clean_attrs(ds[name].attrs)
    encoding = {}
    if compress:
        for name, var in ds.data_vars.items():
            if var.dtype.kind in "fiub" and var.ndim > 0:
                encoding[name] = {"zlib": True, "complevel": 4}
    fd, tmp = tempfile.mkstemp(suffix=".nc.part", dir=path.parent)
    os.close(fd)
    try:
        ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return path


def read_netcdf(path) -> xr.Dataset:
    """Open a rockstudy netCDF file fully into memory (and close the file)."""
    with xr.open_dataset(path, engine="netcdf4") as ds:
        return ds.load()


def write_text(text: str, path) -> Path:
    """Write a text file atomically."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(suffix=".part", dir=path.parent)
    with os.fdopen(fd, "w") as fh:
        fh.write(text)
    os.replace(tmp, path)
    return path
