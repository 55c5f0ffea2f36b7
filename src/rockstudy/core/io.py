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

import errno
import os
import tempfile
import threading
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Hashable

import numpy as np

from rockstudy._version import __version__
from rockstudy.core import limits
from rockstudy.core.constants import CF_CONVENTIONS, PAPER_REFERENCE
from rockstudy.core.validation import InputError

if TYPE_CHECKING:  # xarray is imported where a dataset is read (writers get one)
    import xarray as xr


def netcdf_attr(value):
    """A value netCDF can hold as an attribute (bools → int, None → "none", dicts → str).

    Parameters
    ----------
    value : object
        An attribute value; numbers, strings and lists of numbers are returned as they are.
    """
    if isinstance(value, (bool, np.bool_)):
        return int(value)
    if value is None:
        return "none"
    if isinstance(value, (dict, list, tuple)) and not all(isinstance(v, (int, float)) for v in value):
        return str(value)
    return value


def clean_attrs(attrs: dict) -> dict:
    """``attrs`` with every value made one netCDF can hold (:func:`netcdf_attr`).

    Parameters
    ----------
    attrs : dict
        Attributes of a dataset or a variable, by name.
    """
    return {k: netcdf_attr(v) for k, v in attrs.items()}


_UMASK_LOCK = threading.Lock()


def current_umask() -> int:
    """The process's file mode creation mask (read by setting and restoring it)."""
    with _UMASK_LOCK:
        mask = os.umask(0o022)
        os.umask(mask)
    return mask


class OutputError(OSError):
    """An output file could not be written; the one-line message names the file, the reason and where the
    computed result was kept instead."""


def kept_path(path) -> Path:
    """Where :func:`atomic_write` keeps a result it could not write to ``path``: the temporary folder's
    ``rockstudy-kept/`` with the file's name.

    Parameters
    ----------
    path : str or pathlib.Path
        The file that could not be written.
    """
    return Path(tempfile.gettempdir()) / "rockstudy-kept" / Path(path).name


def atomic_write(path, write: Callable[[str], None]) -> Path:
    """Write ``path`` atomically: ``write(tmp)`` fills a temporary file in the same folder, which is
    fsynced, given mode ``0o666 & ~umask`` and renamed over ``path``. Folders are created as needed.

    When the file cannot be written (the path is a folder, its folder cannot be made, the disk is full or
    read-only ...), nothing is left at ``path``, the result is written to :func:`kept_path` instead, and
    :class:`OutputError` says so in one line.

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

    Raises
    ------
    OutputError
        If ``path`` cannot be written (an :class:`OSError`), naming where the result was kept.
    """
    path = Path(path)
    try:
        return _atomic_write(path, write)
    except OSError as exc:
        reason = exc.strerror or str(exc).splitlines()[0]
        if exc.errno == errno.ENOSPC:
            reason = f"the disk is full: {reason}"
        kept = kept_path(path)
        try:
            if kept.resolve() == path.resolve():
                raise exc
            _atomic_write(kept, write)
            where = f"the result was written to {kept} instead"
        except OSError as again:
            where = f"nor to {kept} ({again.strerror or again}): nothing was written"
        error = OutputError(f"{path}: cannot write it ({reason}); {where}")
        error.errno = exc.errno
        raise error from None


def _atomic_write(path: Path, write: Callable[[str], None]) -> Path:
    if path.is_dir():
        raise IsADirectoryError(21, "it is a folder")
    existing = path.parent.absolute()
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        raise NotADirectoryError(20, f"{existing} is a file, not a folder")
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
    and version), ``references`` (the paper, :data:`~rockstudy.core.constants.PAPER_REFERENCE`, after
    the references the data set names itself), ``title`` (kept if present) and ``history``: a line
    naming the writer appended to any history already there. The history line carries no time
    stamp, so that a rerun writes the same file.

    Parameters
    ----------
    attrs : dict
        The dataset's own global attributes; kept, except that ``Conventions`` is replaced and
        ``history`` and ``references`` are extended.
    """
    line = f"written by rockstudy {__version__} (rockstudy.core.io.write_netcdf)"
    history = str(attrs.get("history", "")).strip()
    if line not in history.splitlines():
        history = f"{history}\n{line}" if history else line
    references = str(attrs.get("references", "")).strip()
    if PAPER_REFERENCE not in references:  # the paper, after the references the data set names itself
        references = f"{references}\n{PAPER_REFERENCE}" if references else PAPER_REFERENCE
    return {"Conventions": CF_CONVENTIONS,
            "title": attrs.get("title", "rockstudy dataset"),
            "source": f"rockstudy {__version__}: numerical simulation of rigid rocking blocks with on-off "
                      "controlled anchorages",
            **{k: v for k, v in attrs.items() if k not in ("Conventions", "title", "history", "references")},
            "references": references,
            "history": history}


def check_coordinates(ds: xr.Dataset) -> None:
    """Raise ``ValueError`` unless every numeric one-dimensional coordinate variable (a variable
    named after its dimension) is strictly monotonic, as CF §1.2 requires.

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset to check; it is not changed.
    """
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

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset to write; a copy gets the CF attributes, ``ds`` itself is not changed.
    path : str or pathlib.Path
        The netCDF file to write; its folder is created as needed.
    compress : bool, default True
        Compress the numeric data variables with zlib (level 4).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    check_coordinates(ds)
    ds = ds.copy()
    ds.attrs = clean_attrs(cf_attributes(ds.attrs))
    for name in list(ds.variables):
        ds[name].attrs = clean_attrs(ds[name].attrs)
    encoding: dict[Hashable, dict[str, object]] = {name: {"_FillValue": None} for name in ds.coords}
    if compress:
        for name, var in ds.data_vars.items():
            if var.dtype.kind in "fiub" and var.ndim > 0:
                encoding[name] = {"zlib": True, "complevel": 4}

    def write(tmp):
        try:
            ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
        except RuntimeError as exc:  # the netCDF library's own errors (an HDF error on a full disk): an OSError
            raise OSError(errno.EIO, f"netCDF: {str(exc).splitlines()[0] if str(exc) else 'write failed'}") from exc
    return atomic_write(path, write)


def declared_sizes(path) -> dict:
    """The number of values each variable of a netCDF file declares, read from its header alone (nothing
    is loaded: a file of a few kB may declare billions of unwritten values).

    Parameters
    ----------
    path : str or pathlib.Path
        The netCDF file.

    Returns
    -------
    dict
        ``{variable: (values, bytes per value, dimensions)}``.
    """
    import netCDF4

    try:
        with netCDF4.Dataset(path) as nc:
            return {name: (int(var.size), int(getattr(var.dtype, "itemsize", 8) or 8), tuple(var.dimensions))
                    for name, var in nc.variables.items()}
    except OSError as exc:
        raise InputError(f"{path}: not a netCDF file ({exc.strerror or exc})") from None


def check_declared_sizes(path, variables=None, max_values: int = limits.MAX_DATASET_VALUES,
                         max_bytes: int = limits.MAX_DATASET_BYTES) -> None:
    """Refuse, in one line naming the file and the variable, a netCDF file whose header declares a variable
    of more than ``max_values`` values, or variables (``variables`` only, if given) of more than
    ``max_bytes`` bytes together, before anything is loaded.

    Parameters
    ----------
    path : str or pathlib.Path
        The netCDF file.
    variables : iterable of str, optional
        The variables that will be loaded (their dimensions' coordinates count too); None: all.
    max_values : int, optional
        Most values of one variable (default :data:`rockstudy.core.limits.MAX_DATASET_VALUES`).
    max_bytes : int, optional
        Most bytes of the variables loaded together (default :data:`rockstudy.core.limits.MAX_DATASET_BYTES`).
    """
    sizes = declared_sizes(path)
    if variables is None:
        wanted = sizes
    else:  # the variables asked for, their dimensions' coordinates, and every dimension coordinate (xarray
        # loads those when it opens the file)
        names = set(variables)
        names |= {dim for name in list(names) if name in sizes for dim in sizes[name][2]}
        names |= {name for name, (_, _, dims) in sizes.items() if dims == (name,)}
        wanted = {k: sizes[k] for k in sizes if k in names}
    for name, (values, _, _) in wanted.items():
        if values > max_values:
            raise InputError(f"{path}: variable {name!r} declares {values:.3g} values, the limit is {max_values:.3g}; "
                             "this is not a rockstudy dataset")
    total = sum(values * width for values, width, _ in wanted.values())
    if total > max_bytes:
        raise InputError(f"{path}: the variables declare {total / 2**30:.3g} GiB, the limit is "
                         f"{max_bytes / 2**30:.3g} GiB; this is not a rockstudy dataset")


def read_netcdf(path, variables=None) -> xr.Dataset:
    """Open a rockstudy netCDF file into memory (and close the file): the sizes its header declares are
    checked first (:func:`check_declared_sizes`), and only ``variables`` (and their coordinates) are
    loaded when given. A folder, a FIFO or a device is refused at once (``ValueError`` naming the path),
    never opened.

    Parameters
    ----------
    path : str or pathlib.Path
        The netCDF file to read.
    variables : iterable of str, optional
        The data variables the caller uses; None: all of them.
    """
    import stat
    if not stat.S_ISREG(os.stat(path).st_mode):
        raise ValueError(f"{path}: not a regular file (a folder, a FIFO or a device); give a netCDF file")
    import xarray as xr

    if variables is not None:
        variables = list(variables)
        missing = sorted(set(variables) - set(declared_sizes(path)))
        if missing:
            raise InputError(f"{path}: no variable {', '.join(map(repr, missing))}; is it the right dataset?")
    check_declared_sizes(path, variables)  # from the header, before xarray opens (and indexes) anything
    with xr.open_dataset(path, engine="netcdf4") as ds:
        return (ds[variables] if variables is not None else ds).load()


def write_text(text: str, path) -> Path:
    """Write a text file (CSV, Markdown) atomically (:func:`atomic_write`), UTF-8.

    Parameters
    ----------
    text : str
        The whole content of the file.
    path : str or pathlib.Path
        The file to write; its folder is created as needed.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    def write(tmp):
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)
    return atomic_write(path, write)


# --- "is this the dataset the step expects?" ------------------------------------------------------
COORDINATE_EXPECTATIONS = ("realisation", "frequency_ratio", "strategy", "sampling_time", "delay", "reading", "R",
                           "alpha", "kappa_max", "damping_ratio")
"""Expectation keys compared with a coordinate's values (a list) instead of an attribute."""


class DatasetMismatch(ValueError):
    """A dataset is not the one a step expects; the message names the file, the attribute and both values."""

    def __init__(self, path, attribute: str, found, expected):
        super().__init__(f"{path}: {attribute} is {found!r}, expected {expected!r}: this file was made under "
                         "other settings than the step that reads it (a stale, swapped or hand-made file); "
                         "delete it and rerun to rebuild it")
        self.path, self.attribute, self.found, self.expected = str(path), attribute, found, expected


def same_value(found, expected) -> bool:
    """Equal values: numbers within 1e-9 relative, lists element by element, "none" equal to None.

    Parameters
    ----------
    found : object
        The value read from a dataset (an attribute or a coordinate's values).
    expected : object
        The value the step expects: a number, a string, None or a list of them.
    """
    if isinstance(expected, (list, tuple, np.ndarray)):
        found = np.asarray(found).ravel().tolist() if isinstance(found, (list, tuple, np.ndarray)) else [found]
        return len(found) == len(expected) and all(same_value(f, e) for f, e in zip(found, expected))
    expected, found = netcdf_attr(expected), netcdf_attr(found.item() if isinstance(found, np.generic) else found)
    if isinstance(expected, (int, float)) and not isinstance(found, str):
        try:
            return bool(np.isclose(float(found), float(expected), rtol=1e-9, atol=1e-12))
        except (TypeError, ValueError):
            return False
    return found == expected


def _found(ds: xr.Dataset, key: str):
    if key in COORDINATE_EXPECTATIONS and key in ds.coords:
        return ds[key].values.tolist()
    if key in ds.attrs:
        value = ds.attrs[key]
        return value.tolist() if isinstance(value, (np.ndarray, np.generic)) else value
    if key in ds.coords and ds[key].ndim == 0:  # a scalar coordinate such as strategy or noise_level
        return ds[key].item()
    return _MISSING


_MISSING = "<missing>"


def check_dataset(ds: xr.Dataset, path, expected: dict | None) -> xr.Dataset:
    """``ds`` (read from ``path``) is the dataset a workflow step expects: every key of ``expected`` is an
    attribute, a scalar coordinate or (``realisation``, ``frequency_ratio``) a coordinate of ``ds`` with
    the expected value (numbers to 1e-9 relative). Returns ``ds``.

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset read.
    path : str or pathlib.Path
        The file ``ds`` was read from, named in the error message.
    expected : dict or None
        Expected values by attribute or coordinate name; None or empty checks nothing.

    Raises
    ------
    DatasetMismatch
        Naming the file, the first attribute that differs, its value and the expected one.
    """
    for key, value in (expected or {}).items():
        found = _found(ds, key)
        if found is _MISSING or not same_value(found, value):
            raise DatasetMismatch(path, key, found, value)
    return ds


def read_checked(path, expectations: dict | None) -> xr.Dataset:
    """:func:`read_netcdf` then :func:`check_dataset` against ``expectations[str(path)]``: a mapping from
    file names to expected attributes, as the workflow's ``expect`` parameter gives it for every input.

    Parameters
    ----------
    path : str or pathlib.Path
        The netCDF file to read; ``str(path)`` must be a key of ``expectations``.
    expectations : dict
        Expected attributes (a dict, see :func:`check_dataset`) by file name.

    Raises
    ------
    KeyError
        If ``path`` has no entry (the step would read a file nobody said what it must be).
    DatasetMismatch
        If the file is not the expected dataset.
    """
    if expectations is None or str(path) not in expectations:
        raise KeyError(f"{path}: no expectation for this input (known: {', '.join(sorted(expectations or {}))})")
    return check_dataset(read_netcdf(path), path, expectations[str(path)])


def reader(expectations: dict) -> Callable:
    """``read(path)``: :func:`read_checked` with these ``expectations`` (one per workflow step).

    Parameters
    ----------
    expectations : dict
        Expected attributes by file name, as :func:`read_checked` takes them.
    """
    return lambda path: read_checked(path, expectations)
