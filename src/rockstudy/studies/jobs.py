"""A workflow job's life in the library: its log and resources line (:func:`log_to`,
:func:`resources`), and :func:`open_job`, which every workflow script calls first: the log, a reader
that checks every dataset against what the rule expects of it and against the dataset's own
invariants, and the source fingerprint stamped on what the job writes.

Workflow scripts are thin: ``main(snakemake)`` opens the job, calls one library function and writes
its output, and Snakemake's process runs it through :func:`run`; a test calls ``main`` with a stand-in
object that has the same attributes (``input``, ``output``, ``params``, ``wildcards``, ``log``,
``threads``).
"""
from __future__ import annotations

import atexit
import logging
import math
import os
import sys
import time

from rockstudy.core.frames import with_frame_room

try:
    import resource
except ImportError:  # not on Windows: the resources line then gives the run time only
    resource = None


def log_to(path) -> logging.Logger:
    """Send the "rockstudy" logger (progress, ETA) to ``path``; when the job's process ends, its last
    line gives the job's resources (:func:`resources`: run time, CPU time, peak memory).

    Parameters
    ----------
    path : str or pathlib.Path
        The job's log file; it is overwritten.
    """
    handler = logging.FileHandler(path, mode="w")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
    logger = logging.getLogger("rockstudy")
    logger.addHandler(handler)
    logger.setLevel(logging.INFO)
    atexit.unregister(_log_resources)  # one resources line, however often a job calls log_to
    atexit.register(_log_resources, logger)
    global _JOB_LOGGER
    _JOB_LOGGER = logger
    return logger


_JOB_LOGGER: logging.Logger | None = None
"""The logger :func:`log_to` sent to a job's log: the resources line goes there."""


def run(main, snakemake) -> None:
    """Run a workflow script's ``main(snakemake)`` as the job's whole process, then end the process at once.

    Once ``main`` has returned, every output is written and closed (the writers are atomic,
    :func:`rockstudy.core.io.atomic_write`): the job's log gets its resources line, the logs and the standard
    streams are flushed and the process exits with status 0 without the interpreter's teardown, which
    takes 0.1–0.3 s of CPU with numba, xarray and matplotlib loaded, in every job. If ``main`` raises, the
    process ends the ordinary way: the traceback, the resources line and a non-zero exit status. So does a
    process that a profiler or tracer watches (cProfile, coverage), which writes its results at the exit.
    ``main`` runs with room on Python's frame stack (:func:`rockstudy.core.frames.with_frame_room`), so that
    numba, compiling, does not take and give back a chunk of it at every call.

    Parameters
    ----------
    main : callable
        The script's ``main``, called with ``snakemake``.
    snakemake : snakemake.script.Snakemake
        The object Snakemake gives the script.
    """
    with_frame_room(main, snakemake)
    if sys.getprofile() is not None or sys.gettrace() is not None:
        return
    if _JOB_LOGGER is not None:
        atexit.unregister(_log_resources)
        _log_resources(_JOB_LOGGER)
    logging.shutdown()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)


def write_bytecode() -> bool:
    """Write the byte-code of rockstudy's modules next to their sources (``__pycache__``) where it is missing or
    older than its source, so that the jobs that follow load it instead of compiling each module again. Python
    writes it at the first import anyway, unless told not to (``PYTHONDONTWRITEBYTECODE``, usual in
    containers): then every job compiled the modules it imports, about 0.04 s of CPU each. Returns False when
    some could not be written (an installation the user cannot write to), which changes nothing else."""
    import compileall

    return bool(compileall.compile_dir(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), quiet=2))


def resources() -> dict:
    """What this process has used so far, from the operating system's own accounts (nothing sampled):
    ``wall_s`` since it started, ``cpu_s`` (user + system; ``user_s``, ``system_s``) and ``max_rss_mb``,
    its peak resident memory. [s, MB]"""
    if resource is None:
        return {"wall_s": _process_age(), "cpu_s": time.process_time(), "user_s": math.nan, "system_s": math.nan,
                "max_rss_mb": math.nan}
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return {"wall_s": _process_age(), "cpu_s": usage.ru_utime + usage.ru_stime, "user_s": usage.ru_utime,
            "system_s": usage.ru_stime, "max_rss_mb": usage.ru_maxrss / 1024.0}  # ru_maxrss: kB on Linux


_STARTED = time.monotonic()


def _process_age() -> float:
    """Seconds since this process started (Linux: from /proc; elsewhere since rockstudy was imported)."""
    try:
        with open("/proc/self/stat") as f:
            start_ticks = int(f.read().rsplit(")", 1)[1].split()[19])  # field 22, starttime
        with open("/proc/uptime") as f:
            uptime = float(f.read().split()[0])
        return max(0.0, uptime - start_ticks / os.sysconf("SC_CLK_TCK"))
    except (OSError, ValueError, IndexError):
        return time.monotonic() - _STARTED


def _log_resources(logger: logging.Logger) -> None:
    r = resources()
    logger.info("resources: %.1f s run time, %.1f s CPU (user %.1f, system %.1f), peak memory %.0f MB",
                r["wall_s"], r["cpu_s"], r["user_s"], r["system_s"], r["max_rss_mb"])


class Job:
    """An open workflow job (:func:`open_job`): its logger, its checked reader and its fingerprint stamp."""

    def __init__(self, snakemake, logger: logging.Logger):
        self.snakemake = snakemake
        self.params = snakemake.params
        self.logger = logger
        self.expectations = dict(getattr(snakemake.params, "expect", None) or {})

    def read(self, path):
        """The netCDF input ``path``, checked against what the rule expects of it
        (:func:`rockstudy.core.io.read_checked`) and against its own invariants
        (:func:`rockstudy.studies.datasets.check_invariants`).

        Parameters
        ----------
        path : str or pathlib.Path
            A netCDF input of the job; a key of the rule's ``params.expect``.

        Raises
        ------
        KeyError
            If the rule states no expectation for ``path``.
        ValueError
            (:class:`~rockstudy.core.io.DatasetMismatch`, :class:`~rockstudy.studies.datasets.InconsistentDataset`)
            naming the file and what differs.
        """
        from rockstudy.core import io
        from rockstudy.studies.datasets import check_invariants

        return check_invariants(io.read_checked(path, self.expectations), path)

    def read_all(self, paths) -> list:
        """:meth:`read` of every path, in order.

        Parameters
        ----------
        paths : iterable of str or pathlib.Path
            The netCDF inputs, each a key of the rule's ``params.expect``.
        """
        return [self.read(path) for path in paths]

    def stamp(self, ds, fingerprint: str = "library"):
        """``ds`` with the source fingerprint it was made with (the rule's ``params.<fingerprint>``) in its
        ``rockstudy_source_sha256`` attribute; returns ``ds``.

        Parameters
        ----------
        ds : xarray.Dataset
            The dataset the job writes; its attributes are changed in place.
        fingerprint : str, default "library"
            Name of the rule's parameter that holds the fingerprint (``params.<fingerprint>``).
        """
        ds.attrs["rockstudy_source_sha256"] = getattr(self.params, fingerprint)
        return ds


def open_job(snakemake, *, compiled: bool = False) -> Job:
    """Open a workflow job: send the "rockstudy" logger to the job's log (:func:`log_to`), give numba the
    job's threads when it runs ``compiled`` code, and return the :class:`Job` whose reader checks every
    input against the rule's ``params.expect`` (``{file: expected attributes}``, from
    :class:`rockstudy.studies.expectations.StudyExpectations`).

    Parameters
    ----------
    snakemake : snakemake.script.Snakemake
        The object Snakemake gives a script, or any object with the same attributes (``log``, ``params``,
        ``threads``): a test calls a script's ``main`` with a stand-in.
    compiled : bool, default False
        Whether the job runs numba-compiled code; then numba uses the job's ``threads``.
    """
    logger = log_to(snakemake.log[0])
    if compiled:
        import numba

        numba.set_num_threads(snakemake.threads)
    return Job(snakemake, logger)
