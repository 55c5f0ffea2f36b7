"""The checks no single input's range covers: relations between inputs (a grid's start, stop and step, the
amplitude scan and its resolution, a_max,0 within the scan, a slender block) and the size of the work (the
simulations and the noise records one command or job may take, the entries of a config's lists).

They raise :class:`~rockstudy.core.checks.InputError` naming the input, the value and what is allowed, before
any work; :mod:`rockstudy.core.validation` gives them under its own name too.
"""
from __future__ import annotations

import math
import os

from rockstudy.core.checks import InputError, _fmt, check_positive, fail
from rockstudy.core.limits import (
    MAX_AMPLITUDE_RATIO,
    MAX_GRID_POINTS,
    MAX_LIST_ITEMS,
    MAX_SIMULATIONS,
    MIN_RELATIVE_RESOLUTION,
    RECORD_DT,
)


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


def check_block(block, name: str = "block", restitution_name: str | None = None) -> None:
    """Physical meaning of a block: Housner's restitution e = 1 - 1.5 sin^2(alpha) (Eq. 14) must lie in
    [0, 1], i.e. a slender block with H/B >= 1/sqrt(2); a squat block needs an explicit restitution.

    Parameters
    ----------
    block : rockstudy.Block
        The block, or any object with its ``width``, ``height``, ``alpha``, ``restitution`` and
        ``housner_restitution``.
    name : str, optional
        The block's name in the message (default ``"block"``).
    restitution_name : str, optional
        The name of its restitution in the message (default ``"<name>.restitution"``).
    """
    if block.restitution is None and block.housner_restitution < -1e-12:  # e = 0 at H/B = 1/sqrt(2)
        raise InputError(
            f"{name}: width {block.width:g} m and height {block.height:g} m give alpha = "
            f"{math.degrees(block.alpha):.1f} deg and Housner's restitution e = 1 - 1.5 sin^2(alpha) = "
            f"{block.housner_restitution:.3g} < 0 (Eq. 14); the model needs a slender block (height/width >= "
            f"{1 / math.sqrt(2):.3f}) or an explicit {restitution_name or name + '.restitution'} in [0, 1]")


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
