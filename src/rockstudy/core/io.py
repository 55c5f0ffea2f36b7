"""Dataset I/O: the one place where rockstudy writes and reads files.

Every data product (netCDF, PNG, PDF, CSV, Markdown) goes through :func:`atomic_write`: a
temporary file in the same folder, flushed to disk (fsync), given the mode the umask allows
(0666 & ~umask, like any file the user creates; ``mkstemp`` alone would leave 0600), then
renamed over the target with ``os.replace``. An interrupted or failed write never leaves a
half-written file behind, and an existing file is kept until the new one is complete.

Every netCDF file goes through :func:`write_netcdf`, which makes it CF-1.11 conforming: the global
attributes ``Conventions``, ``title``, ``source``, ``history`` and ``references`` (the paper), no
``_FillValue`` on coordinate variables, and a check that every one-dimensional coordinate is
strictly monotonic (CF §1.2) before anything is written.
"""
from __future__ import annotations

import os
import tempfile
import threading
from pathlib import Path
from typing import Callable

import numpy as np
import xarray as xr

from rockstudy._version import __version__
from rockstudy.core.constants import CF_CONVENTIONS, PAPER_REFERENCE


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


_UMASK_LOCK = threading.Lock()


def current_umask() -> int:
    """The process's file mode creation mask (read by setting and restoring it)."""
    with _UMASK_LOCK:
        mask = os.umask(0o022)
        os.umask(mask)
    return mask


def atomic_write(path, write: Callable[[str], None]) -> Path:
    """Write ``path`` atomically: ``write(tmp)`` fills a temporary file in the same folder, which is
    fsynced, given mode ``0o666 & ~umask`` and renamed over ``path``. Folders are created as needed.

    Parameters
    ----------
    path : str or Path
        Target file.
    write : callable
        Called with the temporary file's name; it must write the whole content there.

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    os.close(fd)
    try:
        write(tmp)
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o666 & ~current_umask())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    try:  # make the rename itself durable
        dir_fd = os.open(path.parent, os.O_RDONLY)
        try:
            os.fsync(dir_fd)
        finally:
            os.close(dir_fd)
    except OSError:  # pragma: no cover - some filesystems do not fsync folders
        pass
    return path


def cf_attributes(attrs: dict) -> dict:
    """``attrs`` with the CF global attributes rockstudy adds to every netCDF file.

    ``Conventions`` (:data:`~rockstudy.core.constants.CF_CONVENTIONS`), ``source`` (the package
    and version), ``references`` (the paper, :data:`~rockstudy.core.constants.PAPER_REFERENCE`),
    ``title`` (kept if present) and ``history``: a line naming the writer appended to any history
    already there. The history line carries no time stamp, so that a rerun writes the same file.
    """
    line = f"written by rockstudy {__version__} (rockstudy.core.io.write_netcdf)"
    history = str(attrs.get("history", "")).strip()
    if line not in history.splitlines():
        history = f"{history}\n{line}" if history else line
    return {"Conventions": CF_CONVENTIONS,
            "title": attrs.get("title", "rockstudy dataset"),
            "source": f"rockstudy {__version__}: numerical simulation of rigid rocking blocks with on-off "
                      "controlled anchorages",
            "references": PAPER_REFERENCE,
            **{k: v for k, v in attrs.items() if k not in ("Conventions", "title", "history")},
            "history": history}


def check_coordinates(ds: xr.Dataset) -> None:
    """Raise ``ValueError`` unless every numeric one-dimensional coordinate variable (a variable
    named after its dimension) is strictly monotonic, as CF §1.2 requires."""
    for name in ds.dims:
        if name not in ds.variables or ds[name].dtype.kind not in "fiu" or ds[name].size < 2:
            continue
        step = np.diff(ds[name].values)
        if not (np.all(step > 0) or np.all(step < 0)):
            raise ValueError(f"coordinate {name!r} is not strictly monotonic ({int(np.sum(step == 0))} repeated "
                             f"values): CF coordinates need one value per index")


def write_netcdf(ds: xr.Dataset, path, *, compress: bool = True) -> Path:
    """Write ``ds`` to ``path`` atomically (:func:`atomic_write`) as a CF-1.11 file.

    Global attributes get :func:`cf_attributes`; coordinates are written without ``_FillValue``
    (CF §2.5.1) and must be strictly monotonic (:func:`check_coordinates`); data variables are
    zlib-compressed when ``compress``.
    """
    check_coordinates(ds)
    ds = ds.copy()
    ds.attrs = clean_attrs(cf_attributes(ds.attrs))
    for name in list(ds.variables):
        ds[name].attrs = clean_attrs(ds[name].attrs)
    encoding = {name: {"_FillValue": None} for name in ds.coords}
    if compress:
        for name, var in ds.data_vars.items():
            if var.dtype.kind in "fiub" and var.ndim > 0:
                encoding[name] = {"zlib": True, "complevel": 4}
    return atomic_write(path, lambda tmp: ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding))


def read_netcdf(path) -> xr.Dataset:
    """Open a rockstudy netCDF file fully into memory (and close the file)."""
    with xr.open_dataset(path, engine="netcdf4") as ds:
        return ds.load()


def write_text(text: str, path) -> Path:
    """Write a text file (CSV, Markdown) atomically (:func:`atomic_write`), UTF-8."""
    def write(tmp):
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)
    return atomic_write(path, write)
