"""Readers look at the sizes a netCDF header declares before loading, and load only what they use: generated
over small files (a few kB, written by netCDF4 itself) declaring a variable of more values than a rockstudy
dataset ever holds, in every role (data variable, dimension coordinate, 2-D variable) and type. Each is refused
within 2 s in one line naming the variable, never a ``MemoryError``; a huge variable the caller does not use
is not loaded at all.
"""
from __future__ import annotations

import time

import netCDF4
import numpy as np
import pytest

from rockstudy.core import io, limits
from rockstudy.core.validation import InputError

SIZES = (limits.MAX_DATASET_VALUES + 1, 2_400_000_000, 10**12)
TYPES = ("f8", "f4", "i8")
ROLES = ("data", "coordinate", "2-D")


def _write(path, values: int, dtype: str, role: str, small: bool = True) -> str:
    """A netCDF4 file whose header declares a variable of ``values`` values, none of them written."""
    with netCDF4.Dataset(path, "w") as nc:
        if small:
            nc.createDimension("strategy", 2)
            var = nc.createVariable("fragility_median", "f8", ("strategy",))
            var[:] = [0.4, 0.5]
        if role == "2-D":
            nc.createDimension("a", 1000)
            nc.createDimension("b", values // 1000 + 1)
            nc.createVariable("huge", dtype, ("a", "b"), chunksizes=(1, 4096))
            return "huge"
        nc.createDimension("n", values)
        name = "n" if role == "coordinate" else "huge"
        nc.createVariable(name, dtype, ("n",), chunksizes=(min(4096, values),))
        return name


CASES = [pytest.param(v, t, r, id=f"{v:.0e}-{t}-{r}") for v in SIZES for t in TYPES for r in ROLES]


@pytest.mark.parametrize(("values", "dtype", "role"), CASES)
def test_a_small_file_declaring_a_huge_variable_is_refused_in_one_line(values, dtype, role, tmp_path):
    path = tmp_path / "devices.nc"
    name = _write(path, values, dtype, role)
    assert path.stat().st_size < 100_000
    t0 = time.perf_counter()
    with pytest.raises(InputError) as refused:
        io.read_netcdf(path)
    assert time.perf_counter() - t0 < 2.0
    text = str(refused.value)
    assert len(text.splitlines()) == 1 and repr(name) in text and str(path) in text, text


@pytest.mark.parametrize("values", SIZES, ids=lambda v: f"{v:.0e}")
def test_only_the_variables_used_are_loaded(values, tmp_path):
    path = tmp_path / "devices.nc"
    _write(path, values, "f8", "data")
    ds = io.read_netcdf(path, variables=["fragility_median"])
    assert list(ds.data_vars) == ["fragility_median"]
    np.testing.assert_array_equal(ds.fragility_median.values, [0.4, 0.5])


def test_a_variable_the_file_lacks_is_named(tmp_path):
    path = tmp_path / "devices.nc"
    _write(path, 10, "f8", "data")
    with pytest.raises(InputError, match="'threshold'"):
        io.read_netcdf(path, variables=["threshold"])
