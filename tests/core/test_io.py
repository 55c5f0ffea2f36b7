"""rockstudy.core.io: the one atomic writer (umask, no partial files), netCDF round trips and attributes."""
import os
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from rockstudy.core import io


def test_netcdf_attr_makes_values_netcdf_can_hold():
    assert io.netcdf_attr(True) == 1 and io.netcdf_attr(np.bool_(False)) == 0
    assert io.netcdf_attr(None) == "none"
    assert io.netcdf_attr({"a": 1}) == "{'a': 1}" and io.netcdf_attr([0.1, 2]) == [0.1, 2]
    assert io.netcdf_attr(["x", 1]) == "['x', 1]"


def test_netcdf_round_trip_keeps_values_units_and_attributes(tmp_path):
    ds = xr.Dataset({"threshold": ("frequency_ratio", [1.2, np.nan, 3.4], {"units": "1"})},
                    coords={"frequency_ratio": ("frequency_ratio", [1.0, 2.0, 3.0], {"long_name": "omega_p/p"})},
                    attrs={"noise_seed": 2**63 - 1, "overturned": True, "band": None})
    back = io.read_netcdf(io.write_netcdf(ds, tmp_path / "sub" / "a.nc"))
    np.testing.assert_array_equal(back["threshold"].values, ds["threshold"].values)  # NaN == NaN here
    assert back["threshold"].attrs["units"] == "1" and back["frequency_ratio"].attrs["long_name"] == "omega_p/p"
    assert back.attrs["noise_seed"] == 2**63 - 1 and back.attrs["overturned"] == 1 and back.attrs["band"] == "none"


def test_write_text_is_utf8(tmp_path):
    path = io.write_text("θ̇ [rad/s]\n", tmp_path / "a.md")
    assert path.read_bytes() == "θ̇ [rad/s]\n".encode("utf-8")


# --- atomic writes follow the umask --------------------------------------------------------------
@pytest.mark.parametrize("umask,mode", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_every_writer_follows_the_umask(tmp_path, umask, mode):
    import matplotlib.pyplot as plt

    from rockstudy.plotting import save_figure
    old = os.umask(umask)
    try:
        ds = xr.Dataset({"x": ("t", np.arange(3.0))})
        paths = [io.write_netcdf(ds, tmp_path / "a.nc"), io.write_text("a,b\n", tmp_path / "a.csv"),
                 io.write_text("| a |\n", tmp_path / "a.md")]
        paths += save_figure(plt.figure(), tmp_path / "a.png", tmp_path / "a.pdf")
    finally:
        os.umask(old)
    for p in paths:
        assert os.stat(p).st_mode & 0o777 == mode, p
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv", "a.md", "a.nc", "a.pdf", "a.png"]


def test_failed_write_keeps_the_old_file_and_leaves_no_part(tmp_path):
    target = io.write_text("old", tmp_path / "t.md")

    def boom(tmp):
        Path(tmp).write_text("half")
        raise RuntimeError("disk full")
    with pytest.raises(RuntimeError):
        io.atomic_write(target, boom)
    assert target.read_text() == "old" and [p.name for p in tmp_path.iterdir()] == ["t.md"]


def _spectrum_like():
    return xr.Dataset({"threshold": ("frequency_ratio", [1.0, 2.0])},
                      coords={"frequency_ratio": [1.0, 2.0], "realisation": [0, 1], "strategy": "FS"},
                      attrs={"noise_seed": 7, "noise_band_hz": "none", "free_time_s": 30.0})


def test_check_dataset_accepts_the_expected_dataset_and_names_the_first_difference(tmp_path):
    ds = _spectrum_like()
    ok = {"noise_seed": 7, "noise_band_hz": None, "free_time_s": 30.0 + 1e-12, "strategy": "FS",
          "realisation": [0, 1], "frequency_ratio": [1.0, 2.0]}
    assert io.check_dataset(ds, "x.nc", ok) is ds
    for key, value in [("noise_seed", 8), ("noise_band_hz", 5.0), ("free_time_s", 10.0), ("strategy", "CS01"),
                       ("realisation", [0, 1, 2]), ("frequency_ratio", [1.0, 2.5]), ("block_alpha", 0.2)]:
        with pytest.raises(io.DatasetMismatch, match=f"x.nc: {key} is .*, expected {re.escape(repr(value))}"):
            io.check_dataset(ds, "x.nc", {**ok, key: value})


def test_read_checked_needs_an_expectation_for_every_file(tmp_path):
    path = io.write_netcdf(_spectrum_like(), tmp_path / "s.nc")
    assert float(io.read_checked(path, {str(path): {"noise_seed": 7}})["threshold"][1]) == 2.0
    with pytest.raises(KeyError, match="no expectation"):
        io.read_checked(path, {})
    with pytest.raises(io.DatasetMismatch, match="noise_seed is 7, expected 8"):
        io.reader({str(path): {"noise_seed": 8}})(path)
