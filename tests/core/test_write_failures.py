"""Every way writing an output can fail, generated over the writers (netCDF, text) and the failures (the path is
a folder, its folder is a file, the disk is full at write or at sync, the filesystem is read-only, the rename
is refused): one line naming the file and the reason, nothing partial at the path or beside it, and the
computed result kept whole where the message says.
"""
from __future__ import annotations

import errno
import os
import tempfile

import numpy as np
import pytest
import xarray as xr

from rockstudy.core import io


def _dataset():
    return xr.Dataset({"threshold": ("frequency_ratio", np.array([1.5, 2.5]), {"units": "1"})},
                      coords={"frequency_ratio": ("frequency_ratio", [1.0, 2.0], {"units": "1"})})


WRITERS = {
    "netcdf": (lambda path: io.write_netcdf(_dataset(), path),
               lambda path: xr.open_dataset(path).threshold.values.tolist() == [1.5, 2.5]),
    "text": (lambda path: io.write_text("a,b\n1,2\n", path), lambda path: open(path).read() == "a,b\n1,2\n"),
}


def _folder(tmp_path, monkeypatch):
    path = tmp_path / "out.nc"
    path.mkdir()
    return path


def _file_parent(tmp_path, monkeypatch):
    (tmp_path / "results").write_text("a file where the folder should be")
    return tmp_path / "results" / "sub" / "out.nc"


def _disk_full_at_sync(tmp_path, monkeypatch):
    calls = []
    real = os.fsync

    def full(fd):
        calls.append(fd)
        if len(calls) == 1:  # the first write fails; the kept copy may be written
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return real(fd)
    monkeypatch.setattr(os, "fsync", full)
    return tmp_path / "out.nc"


def _once(module, name, code):
    def install(tmp_path, monkeypatch):
        real = getattr(module, name)
        calls = []

        def broken(*args, **kwargs):
            calls.append(1)
            if len(calls) == 1:
                raise OSError(code, os.strerror(code))
            return real(*args, **kwargs)
        monkeypatch.setattr(module, name, broken)
        return tmp_path / "out.nc"
    return install


FAILURES = {
    "path-is-a-folder": _folder,
    "folder-is-a-file": _file_parent,
    "disk-full-at-sync": _disk_full_at_sync,
    "read-only-filesystem": _once(tempfile, "mkstemp", errno.EROFS),
    "rename-refused": _once(os, "replace", errno.EACCES),
    "disk-full-at-chmod": _once(os, "chmod", errno.ENOSPC),
}


@pytest.mark.parametrize(("writer", "failure"), [(w, f) for w in WRITERS for f in FAILURES])
def test_a_failed_write_is_one_line_and_keeps_the_result(writer, failure, tmp_path, monkeypatch):
    kept_dir = tmp_path / "tmp"
    kept_dir.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(kept_dir))
    write, read_back = WRITERS[writer]
    path = FAILURES[failure](tmp_path, monkeypatch)
    path = path.with_suffix(".nc" if writer == "netcdf" else ".csv") if not path.is_dir() else path
    with pytest.raises(OSError) as failed:
        write(path)
    monkeypatch.undo()
    text = str(failed.value)
    assert len(text.splitlines()) == 1 and str(path) in text, text
    kept = kept_dir / "rockstudy-kept" / path.name
    assert str(kept) in text, text
    assert read_back(kept)
    leftovers = [p.name for p in path.parent.glob(".*part")] if path.parent.is_dir() else []
    assert not leftovers and (not path.exists() or path.is_dir())
