"""The checks every input goes through: numbers, relations between inputs, the size of the work, files.

A numeric input's type, unit and range are declared once in :mod:`rockstudy.core.quantities`, and every
limit is written once in :mod:`rockstudy.core.limits` (its names are aliased here, ``validation.MAX_TIME_SPAN``,
for the modules that read them beside the checks). This module holds the low-level checks the
declarations call (:func:`check_number`, :func:`check_range`, :func:`check_int_range`), and the checks no
single input's range covers: relations between inputs (a grid's start, stop and step, a_max,0 within the
amplitude scan), the size of the work (:func:`check_workload`, :func:`check_sizes`) and the files read and
written.

Every check takes the name the user typed (``--frequency-step``, ``frequency_grid.step``,
``Block.width``), the value, and the unit the user gave it in, and raises :class:`InputError`
(a :class:`ValueError`) whose message names the input, the value and what is allowed. The checks
run before any work, so a bad input never costs a computation and never leaves a partial output.
:func:`memory_budget` bounds the noise records one command or job holds at once (a quarter of the machine's
physical memory).
"""
from __future__ import annotations

import math
import numbers
import os
import tempfile
from pathlib import Path

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


class InputError(ValueError):
    """A value the user gave is not allowed; the message names the input, the value and the rule."""


def _fmt(value) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    return repr(value) if isinstance(value, str) else str(value)


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


def field_names(owner: str, names=None):
    """The name of each field of ``owner`` in messages: ``names[field]`` (the caller's option or config key,
    e.g. ``"--kappa-max"`` or ``"anchorage.kappa_max"``), else ``"<owner>.<field>"``.

    Parameters
    ----------
    owner : str
        The class whose fields are named (``"Anchorage"``).
    names : dict, optional
        The caller's name of a field in messages (``{"kappa_max": "--kappa-max"}``); None: every field is
        named ``"<owner>.<field>"``.

    Returns
    -------
    callable
        A function of a field name that returns its name in messages.
    """
    names = names or {}
    return lambda field: names.get(field, f"{owner}.{field}")


def fail(name: str, value, allowed: str, unit: str = ""):
    """Raise :class:`InputError` ``"<name> = <value> <unit> is not allowed: <allowed>"``.

    Parameters
    ----------
    name : str
        The input as the user knows it (``"--kappa-max"``, ``"frequency_grid.step"``).
    value : object
        The value given; a float is written with 6 significant digits, a str quoted.
    allowed : str
        What is allowed, or why the value is refused.
    unit : str, optional
        The unit written after the value ("" for none).

    Raises
    ------
    InputError
        Always.
    """
    raise InputError(f"{name} = {_fmt(value)}{_unit(unit)} is not allowed: {allowed}")


def check_number(name: str, value, unit: str = "") -> float:
    """A finite real number (not a bool, not NaN or inf), returned as a float.

    Parameters
    ----------
    name : str
        The input's name in the message.
    value : object
        The value given.
    unit : str, optional
        The value's unit in the message ("" for none).
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        fail(name, value, "it must be a number")
    value = float(value)
    if not math.isfinite(value):
        fail(name, value, "it must be a finite number (not NaN or inf)", unit)
    return value


def check_range(name: str, value, low: float | None = None, high: float | None = None, unit: str = "", *,
                low_open: bool = False, high_open: bool = False, why: str = "") -> float:
    """A finite number in [low, high], returned as a float.

    Parameters
    ----------
    name : str
        The input's name in the message.
    value : object
        The value given.
    low, high : float or None, optional
        The range's ends; None: unbounded on that side. [unit]
    unit : str, optional
        The unit of the value and the ends, in the message ("" for none).
    low_open, high_open : bool, optional
        Whether the end itself is excluded (default: both included).
    why : str, optional
        Why the range is what it is, appended to the message in parentheses.
    """
    value = check_number(name, value, unit)
    too_low = low is not None and (value <= low if low_open else value < low)
    too_high = high is not None and (value >= high if high_open else value > high)
    if too_low or too_high:
        lo = "" if low is None else f"{_fmt(low)} {'<' if low_open else '<='} "
        hi = "" if high is None else f" {'<' if high_open else '<='} {_fmt(high)}"
        fail(name, value, f"allowed is {lo}{name}{hi}{_unit(unit)}" + (f" ({why})" if why else ""), unit)
    return value


def check_positive(name: str, value, unit: str = "", high: float | None = None, why: str = "") -> float:
    """A finite number > 0 (and <= ``high``), returned as a float.

    Parameters
    ----------
    name : str
        The input's name in the message.
    value : object
        The value given.
    unit : str, optional
        The unit of the value and of ``high``, in the message ("" for none).
    high : float, optional
        The largest value allowed; None: no upper bound. [unit]
    why : str, optional
        Why the limit is what it is, appended to the message in parentheses.
    """
    return check_range(name, value, 0.0, high, unit, low_open=True, why=why)


def check_nonnegative(name: str, value, unit: str = "", high: float | None = None, why: str = "") -> float:
    """A finite number >= 0 (and <= ``high``), returned as a float.

    Parameters
    ----------
    name : str
        The input's name in the message.
    value : object
        The value given.
    unit : str, optional
        The unit of the value and of ``high``, in the message ("" for none).
    high : float, optional
        The largest value allowed; None: no upper bound. [unit]
    why : str, optional
        Why the limit is what it is, appended to the message in parentheses.
    """
    return check_range(name, value, 0.0, high, unit, why=why)


def check_int_range(name: str, value, low: int = 0, high: int = MAX_INTEGER, why: str = "") -> int:
    """An integer (an int, or a float with an integer value) in [low, high], returned as an int.

    Parameters
    ----------
    name : str
        The input's name in the message.
    value : object
        The value given; a bool is refused.
    low, high : int, optional
        The smallest and largest values allowed, both included (default 0 and :data:`MAX_INTEGER`).
    why : str, optional
        Why the range is what it is, appended to the message in parentheses.
    """
    if isinstance(value, bool):
        fail(name, value, "it must be an integer")
    if isinstance(value, numbers.Integral):
        value = int(value)
    elif isinstance(value, numbers.Real) and math.isfinite(value) and float(value).is_integer():
        value = int(float(value))
    else:
        fail(name, value, f"it must be an integer in [{low}, {high}]")
    if not (low <= value <= high):
        fail(name, value, f"allowed is {low} <= {name} <= {high}" + (f" ({why})" if why else ""))
    return value


def check_items(name: str, values, low: int = 1, what: str = "item"):
    """A sequence of at least ``low`` items (a list, a tuple, an array, any iterable): empty data is refused,
    never turned into a number.

    Parameters
    ----------
    name : str
        The argument's name in the message (``"records"``).
    values : iterable
        The items given; a string or a mapping is not a sequence of items.
    low : int, optional
        The fewest items allowed (default 1).
    what : str, optional
        What one item is, in the message (``"record"``).

    Returns
    -------
    sequence
        ``values`` itself when it has a length, else its items as a list.
    """
    if values is None or isinstance(values, (str, bytes, dict)):
        fail(name, values, f"give a sequence of at least {low} {what}(s)")
    try:  # a sized sequence is counted, not copied; an iterator is read into a list
        items = values if hasattr(values, "__len__") else list(values)
        count = len(items)
    except TypeError:
        fail(name, values, f"give a sequence of at least {low} {what}(s)")
    if count < low:
        fail(name, f"{count} {what}(s)", f"give at least {low}")
    return items


def grid_size(start: float, stop: float, step: float) -> int:
    """Number of points of the grid ``start, start + step, ..., <= stop`` (computed without building it).

    Parameters
    ----------
    start, stop : float
        First point and upper bound of the grid, start <= stop.
    step : float
        Spacing of the points, > 0 (a point at most 1e-9 steps above ``stop``, round-off, counts).
    """
    return int(math.floor((stop - start) / step + 1e-9)) + 1


def check_grid(prefix: str, start, stop, step, unit: str = "", *, high: float, max_points: int = MAX_GRID_POINTS,
               strict: bool = False, names: tuple[str, str, str] | None = None) -> int:
    """A grid start..stop by step: finite, 0 < start <= stop <= ``high`` (start < stop if ``strict``),
    step > 0 and at most ``max_points`` points. Returns the number of points.

    Parameters
    ----------
    prefix : str
        The grid's config key (``"frequency_grid"``); its inputs are named ``prefix.start`` ... in messages.
    start, stop, step : float
        The grid's first point, upper bound and spacing. [unit]
    unit : str, optional
        The unit of the three values, in messages ("" for none).
    high : float
        The largest start and stop allowed (keyword only). [unit]
    max_points : int, optional
        The most points the grid may have (default :data:`MAX_GRID_POINTS`).
    strict : bool, optional
        Whether stop must exceed start (a grid of one point is refused).
    names : tuple of str, optional
        The three input names in messages, overriding ``prefix.start``, ``prefix.stop``, ``prefix.step``.
    """
    n_start, n_stop, n_step = names or (f"{prefix}.start", f"{prefix}.stop", f"{prefix}.step")
    start = check_positive(n_start, start, unit, high)
    stop = check_positive(n_stop, stop, unit, high)
    step = check_positive(n_step, step, unit)
    if stop < start or (strict and stop == start):
        fail(n_stop, stop, f"it must be {'>' if strict else '>='} {n_start} = {_fmt(start)}", unit)
    n = grid_size(start, stop, step)
    if n > max_points:
        fail(n_step, step, f"{n_start}..{n_stop} = {_fmt(start)}..{_fmt(stop)} in steps of {_fmt(step)} gives "
                           f"{n if n < 10**15 else f'{float(n):.3g}'} points, the limit is {max_points} (use a step >= "
                           f"{_fmt((stop - start) / (max_points - 1))})", unit)
    return n


def bisection_steps(step: float, resolution: float) -> int:
    """Bisection steps that narrow a bracket of width ``step`` to at most ``resolution`` (0 if it already is).

    Parameters
    ----------
    step : float
        Width of the starting bracket (the coarse scan's step), > 0.
    resolution : float
        Width at which the bisection stops, > 0.
    """
    return max(0, math.ceil(math.log2(step / resolution))) if resolution < step else 0


def check_amplitude_grid(start, stop, step, resolution, names=None) -> int:
    """The upward amplitude scan (ratios a_p/(g tan alpha)); returns the simulations one threshold may need.

    The scan is a grid as in :func:`check_grid` (start < stop <= :data:`MAX_AMPLITUDE_RATIO`), and the
    resolution must not exceed the step nor fall below :data:`MIN_RELATIVE_RESOLUTION` times the stop.

    Parameters
    ----------
    start, stop, step : float
        The coarse scan's first amplitude ratio, upper bound and spacing. [-]
    resolution : float
        Width of a threshold's final bracket, found by bisection after the scan. [-]
    names : tuple of str, optional
        The four input names in messages (default ``amplitude_grid.start``, ``.stop``, ``.step``,
        ``.resolution``).
    """
    names = names or ("amplitude_grid.start", "amplitude_grid.stop", "amplitude_grid.step",
                      "amplitude_grid.resolution")
    n = check_grid("amplitude_grid", start, stop, step, high=MAX_AMPLITUDE_RATIO, strict=True, names=names[:3])
    resolution = check_positive(names[3], resolution)
    if resolution > step:
        fail(names[3], resolution, f"it must not exceed {names[2]} = {_fmt(float(step))}")
    floor = MIN_RELATIVE_RESOLUTION * float(stop)
    if resolution < floor:
        fail(names[3], resolution, f"it must be >= {_fmt(floor)} ({MIN_RELATIVE_RESOLUTION:g} x {names[1]}): "
                                   "floating point cannot bisect a threshold more finely")
    return n + bisection_steps(float(step), resolution)


def memory_budget() -> int:
    """Bytes the noise records of one command or job may take: a quarter of the physical memory. [B]"""
    try:
        total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):  # pragma: no cover - non-POSIX
        total = 8 * 2**30
    return int(total // 4)


def record_samples(durations_s, step: float = RECORD_DT, span: float = 0.0) -> int:
    """Noise record samples of excitations lasting ``durations_s`` read at ``step``, with noise also
    ``span`` after each (the noise reading's step and span). [-]

    Parameters
    ----------
    durations_s : iterable of float
        Duration of each excitation (one record each). [s]
    step : float, optional
        Sampling step of the records (default :data:`RECORD_DT`). [s]
    span : float, optional
        Noise after each excitation's end (default 0). [s]
    """
    extra = int(round(span / step))
    return int(sum(math.ceil(d / step) + 1 + extra for d in durations_s))


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
    import stat
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


def check_workload(name: str, value, n_cases: int, sims_per_case: int, record_bytes: int) -> None:
    """Refuse a command or job whose simulations or noise records exceed :data:`MAX_SIMULATIONS` or
    :func:`memory_budget`.

    Parameters
    ----------
    name : str
        The input that sets the size, named in the message (e.g. ``--realisations``).
    value : object
        That input's value, shown in the message.
    n_cases : int
        Cases of the command or job (realisations x frequencies).
    sims_per_case : int
        Largest number of simulations one case may need (coarse grid points + bisection steps).
    record_bytes : int
        Memory the noise records of the command or job hold at once (0: no records). [B]
    """
    sims = n_cases * sims_per_case
    if sims > MAX_SIMULATIONS:
        fail(name, value, f"{n_cases} cases x up to {sims_per_case} simulations = {sims:.3g} simulations, the "
                          f"limit is {MAX_SIMULATIONS:.0e} (about a day on one core at ~1 ms each)")
    budget = memory_budget()
    if record_bytes > budget:
        fail(name, value, f"the noise records need about {record_bytes / 2**30:.3g} GiB, the limit is "
                          f"{budget / 2**30:.3g} GiB (a quarter of this machine's memory)")


def check_block(block, name: str = "block") -> None:
    """Physical meaning of a block: Housner's restitution e = 1 - 1.5 sin^2(alpha) (Eq. 14) must lie in
    [0, 1], i.e. a slender block with H/B >= 1/sqrt(2); a squat block needs an explicit restitution.

    Parameters
    ----------
    block : rockstudy.Block
        The block, or any object with its ``width``, ``height``, ``alpha``, ``restitution`` and
        ``housner_restitution``.
    name : str, optional
        The block's name in the message (default ``"block"``).
    """
    if block.restitution is None and block.housner_restitution < -1e-12:  # e = 0 at H/B = 1/sqrt(2)
        raise InputError(
            f"{name}: width {block.width:g} m and height {block.height:g} m give alpha = "
            f"{math.degrees(block.alpha):.1f} deg and Housner's restitution e = 1 - 1.5 sin^2(alpha) = "
            f"{block.housner_restitution:.3g} < 0 (Eq. 14); the model needs a slender block (height/width >= "
            f"{1 / math.sqrt(2):.3f}) or an explicit {name}.restitution in [0, 1]")


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


def check_sizes(config, key: str = "", limit: int = MAX_LIST_ITEMS, limits: dict | None = None) -> None:
    """No list or mapping anywhere in ``config`` has more than ``limit`` entries; the message names the key path.

    Parameters
    ----------
    config : object
        A parsed config or part of it; its lists, tuples and dicts are checked recursively.
    key : str, optional
        The key path of ``config`` in messages ("" for the whole config).
    limit : int, optional
        The most entries of a list or mapping (default :data:`MAX_LIST_ITEMS`).
    limits : dict, optional
        Other limits by key path, e.g. ``{"beyond.fragility.records": MAX_SUITE_RECORDS}``.
    """
    if isinstance(config, (list, tuple, dict)):
        most = (limits or {}).get(key, limit)
        if len(config) > most:
            fail(key or "config", f"{len(config)} entries", f"at most {most} entries (each one multiplies the "
                                                           "workflow's jobs, which Snakemake plans before any runs)")
        if isinstance(config, dict):
            for k, item in config.items():
                check_sizes(item, f"{key}.{k}" if key else str(k), limit, limits)
        else:
            for i, item in enumerate(config):
                check_sizes(item, f"{key}[{i}]", limit, limits)


def check_output_path(name: str, path, *, formats: tuple[str, ...] | None = None) -> Path:
    """An output file that can be written: not a folder, not under /proc, /sys or /dev, in a folder that
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


def scan_top(start: float, stop: float, step: float) -> float:
    """Highest amplitude ratio of the upward scan start, start + step, ... <= stop. [-]

    Parameters
    ----------
    start, stop : float
        First amplitude ratio and upper bound of the scan. [-]
    step : float
        Spacing of the scan, > 0. [-]
    """
    return round(start + step * (grid_size(start, stop, step) - 1), 10)


def check_a_max0(name: str, a_max0_g, alpha: float, top: float, top_name: str = "amplitude_grid.stop") -> float:
    """a_max,0 in units of g: positive, finite and, as an amplitude ratio a_max,0/(g tan alpha), not above
    the amplitude scan's top ``top`` (a NaN threshold means "no overturning up to the scan's top"; it
    only counts as >= a_max,0 when the scan reached a_max,0). Returns a_max,0 as an amplitude ratio. [-]

    Parameters
    ----------
    name : str
        The input's name in the message (``"a_max0"``, ``"--a-max0"``).
    a_max0_g : float
        The protection level a_max,0. [g]
    alpha : float
        The block's slenderness. [rad]
    top : float
        Highest amplitude ratio the scan reached (:func:`scan_top`). [-]
    top_name : str, optional
        The input that sets the scan's top, named in the message (default ``"amplitude_grid.stop"``).
    """
    a_max0_g = check_positive(name, a_max0_g, "g")
    ratio = a_max0_g / math.tan(alpha)
    if ratio > top + 1e-9:
        fail(name, a_max0_g, f"it is {ratio:.4g} as an amplitude ratio a/(g tan alpha), above the amplitude scan's "
                             f"top {top:g} ({top_name}); NaN thresholds would then not mean 'no overturning up to "
                             f"a_max0'. Allowed is {name} <= {top * math.tan(alpha):.4g} g, or scan higher", "g")
    return ratio
