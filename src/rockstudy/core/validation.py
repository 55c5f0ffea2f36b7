"""The checks of the files read and written, and the one name under which callers find every check.

The files: a file to read (:func:`check_input_file`: a regular, readable file of bounded size), a results
folder (:func:`check_results_dir`: not a system folder) and an output file (:func:`check_output_path`:
writable, checked before any work). Beside them this module gives, under its own name, the check
primitives of :mod:`rockstudy.core.checks` (:func:`fail`, :func:`check_range`, :class:`InputError` ...),
the relation and work checks of :mod:`rockstudy.core.relations` (:func:`check_grid`,
:func:`check_workload` ...) and the limits of :mod:`rockstudy.core.limits` (``validation.MAX_TIME_SPAN``).
A numeric input's type, unit and range are declared once in :mod:`rockstudy.core.quantities`.

Every check takes the name the user typed (``--frequency-step``, ``frequency_grid.step``,
``Block.width``), the value, and raises :class:`InputError` (a :class:`ValueError`) whose message names
the input, the value and what is allowed, before any work, so a bad input never costs a computation and
never leaves a partial output.
"""
from __future__ import annotations

import os
import stat
import tempfile
from pathlib import Path

from rockstudy.core.checks import (  # noqa: F401 -- the primitives, under this module's name too
    InputError,
    _fmt,
    check_int_range,
    check_items,
    check_nonnegative,
    check_number,
    check_positive,
    check_range,
    fail,
    field_names,
)
from rockstudy.core.limits import (  # noqa: F401 -- the limits, aliased where the checks' callers look
    FIGURE_FORMATS,
    MAX_AMPLITUDE_RATIO,
    MAX_BOOTSTRAP,
    MAX_CONTROLLER_SAMPLES,
    MAX_DAMPING_RATIO,
    MAX_DATASET_BYTES,
    MAX_DEVICES,
    MAX_FREE_TIME,
    MAX_FREQUENCY_RATIO,
    MAX_GRID_POINTS,
    MAX_HISTORY_SAMPLES,
    MAX_INTEGER,
    MAX_JOBS_PER_SPECTRUM,
    MAX_KAPPA,
    MAX_LIST_ITEMS,
    MAX_NOISE_STEP,
    MAX_REALISATIONS,
    MAX_RECORD_BYTES,
    MAX_RECORD_SAMPLES,
    MAX_SIMULATIONS,
    MAX_STEPS,
    MAX_SUITE_RECORDS,
    MAX_TIME_SPAN,
    MIN_RELATIVE_RESOLUTION,
    PSEUDO_FILESYSTEMS,
    RECORD_BYTES_PER_SAMPLE,
    RECORD_DT,
    SYSTEM_FOLDERS,
)
from rockstudy.core.relations import (  # noqa: F401 -- the relation and work checks, under this name too
    bisection_steps,
    check_a_max0,
    check_amplitude_grid,
    check_block,
    check_grid,
    check_sizes,
    check_workload,
    grid_size,
    memory_budget,
    record_samples,
    scan_top,
)


def check_input_file(name: str, path, max_bytes: int) -> Path:
    """A file to read: it exists, is a regular file (not a folder, a FIFO or a device such as /dev/zero,
    which would hang or never end), is readable and holds at most ``max_bytes`` bytes.

    Parameters
    ----------
    name : str
        The input's name in the message (``"--fragility"``, ``"record file"``).
    path : str or pathlib.Path
        The file; ``~`` is expanded.
    max_bytes : int
        The largest file size allowed. [B]

    Returns
    -------
    pathlib.Path
        The path, with ``~`` expanded.
    """
    if path is None or str(path).strip() == "":
        fail(name, path, "give a file name")
    p = Path(path).expanduser()
    try:
        st = os.stat(p)
    except FileNotFoundError:
        fail(name, str(path), "the file does not exist")
    except OSError as exc:
        fail(name, str(path), f"it cannot be read: {exc.strerror or exc}")
    if stat.S_ISDIR(st.st_mode):
        fail(name, str(path), "it is a folder; give a file")
    if not stat.S_ISREG(st.st_mode):
        fail(name, str(path), "it is not a regular file (a FIFO, a socket or a device); give a file")
    if st.st_size > max_bytes:
        fail(name, str(path), f"the file has {st.st_size / 2**20:.4g} MiB, the limit is {max_bytes / 2**20:.4g} MiB")
    if not os.access(p, os.R_OK):
        fail(name, str(path), "the file is not readable")
    return p


def check_results_dir(name: str, path) -> Path:
    """A folder for a study's results: a plain path (no ``{`` ``}``, which Snakemake would read as
    wildcards), not /, not a system folder (:data:`SYSTEM_FOLDERS`, :data:`PSEUDO_FILESYSTEMS`) nor inside
    one, and not an existing file. Returns the path (nothing is created).

    Parameters
    ----------
    name : str
        The input's name in the message (``"results_dir"``).
    path : str
        The folder as given; ``~`` and links are resolved for the checks only.
    """
    if not isinstance(path, str) or path.strip() == "":
        fail(name, path, "give a folder name")
    if "{" in path or "}" in path:
        fail(name, path, "it must not contain '{' or '}' (Snakemake reads them as wildcards)")
    real = os.path.realpath(os.path.expanduser(path))
    if real == os.sep:
        fail(name, path, "it is the root folder /")
    for folder in SYSTEM_FOLDERS + PSEUDO_FILESYSTEMS:
        if real == folder or real.startswith(folder + os.sep):
            fail(name, path, f"it lies in a system folder ({folder}); give a folder of your own")
    if os.path.exists(real) and not os.path.isdir(real):
        fail(name, path, "it is an existing file, not a folder")
    return Path(path)


def check_output_path(name: str, path, *, formats: tuple[str, ...] | None = None) -> Path:
    """An output file that can be written: not a folder, not under /proc, /sys or /dev, not an existing file
    other than a regular one (a FIFO, a socket or a device node anywhere is never replaced), in a folder that
    exists or can be made and where a file can be created (tested by creating and removing one in the
    nearest existing folder; no folder is made by the check), and with one of ``formats`` as its suffix
    if given.

    Parameters
    ----------
    name : str
        The input's name in the message (``"--output"``).
    path : str or pathlib.Path
        The file to write; ``~`` is expanded.
    formats : tuple of str, optional
        The suffixes allowed, lower case without the dot (``("nc",)``, :data:`FIGURE_FORMATS`); None: any.

    Returns
    -------
    pathlib.Path
        The path, with ``~`` expanded.
    """
    if path is None or str(path).strip() == "":
        fail(name, path, "give a file name")
    p = Path(path).expanduser()
    real = os.path.realpath(p)
    if any(real == d or real.startswith(d + os.sep) for d in PSEUDO_FILESYSTEMS):
        fail(name, str(path), f"it lies in a system folder ({', '.join(PSEUDO_FILESYSTEMS)})")
    if p.is_dir():
        fail(name, str(path), "it is a folder; give a file name")
    try:  # stat does not open the file: a FIFO is looked at, never read or written
        mode = os.stat(p).st_mode
    except OSError:  # nothing there yet (or a dangling link): the probe below decides
        mode = None
    if mode is not None and not stat.S_ISREG(mode):
        fail(name, str(path), "it exists and is not a regular file (a FIFO, a socket or a device); give a file name")
    if formats is not None and p.suffix.lstrip(".").lower() not in formats:
        fail(name, str(path), f"the file name must end in {', '.join('.' + f for f in formats)}")
    # the nearest folder that exists: a file is created there as a probe, and nothing is left behind (the
    # missing folders are made by the writer, after every check has passed)
    existing = p.parent.absolute()
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        fail(name, str(path), f"cannot create a file in {existing}: it is a file, not a folder")
    try:
        fd, probe = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".probe", dir=existing)
        os.close(fd)
        os.remove(probe)
    except OSError as exc:
        fail(name, str(path), f"cannot create a file in {existing}: {exc.strerror or exc}")
    if p.exists() and not os.access(p, os.W_OK):
        fail(name, str(path), "the existing file is not writable")
    return p
