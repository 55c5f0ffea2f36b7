"""Overturning spectra (paper §4–5): the minimum overturning amplitude per excitation
frequency, over noise realisations, with overturning maps and convergence in N.

The unsafe region is not monotone in amplitude (there are safe islands above the first
unsafe amplitude), so a threshold is found by an upward scan of a coarse amplitude grid and
a bisection between the last safe and the first overturning grid point, down to a stated
resolution. All amplitudes are ratios a_p / (g·tanα); frequencies are ratios ω_p / p.
"""
from __future__ import annotations

import itertools
import logging
import math
import time
from dataclasses import InitVar, asdict, dataclass, fields

import numba
import numpy as np
import xarray as xr

from rockstudy._version import __version__
from rockstudy.analysis.scenario import Scenario, span_names
from rockstudy.core import validation
from rockstudy.core.constants import PAPER
from rockstudy.core.interrupts import interruptible
from rockstudy.core.limits import MAX_FREQUENCY_RATIO, MAX_GRID_POINTS, MAX_REALISATIONS
from rockstudy.core.quantities import QUANTITIES, SIZES, check_arguments, declares
from rockstudy.engine import _kernel as kernel
from rockstudy.engine.outcome import OUTCOME_MEANINGS, Outcome
from rockstudy.model.excitation import GroundMotion

log = logging.getLogger("rockstudy")

PAPER_EQUATIONS = "Eqs. 1-17 (model), Eq. 23 (excitation), Figs. 5-8 (spectra)"


GRID_FIELDS = ("start", "stop", "step", "resolution")
"""The fields of :class:`AmplitudeGrid`, in order."""


@declares(start="amplitude_ratio", stop="amplitude_ratio", step="amplitude_ratio",
          resolution="amplitude_resolution")
@dataclass(frozen=True)
class AmplitudeGrid:
    """Amplitude ratios a_p/(g·tanα) scanned upward, and the refinement resolution.

    Parameters
    ----------
    start, stop, step : float
        Coarse scan from ``start`` to ``stop`` (inclusive) in ``step``. [-]
    resolution : float
        Width of the final bracket around the threshold. [-]
    names : dict, optional
        The caller's name of each field in error messages (``{"stop": "--max-amplitude-ratio"}``); a field
        missing from it is named ``AmplitudeGrid.<field>``. Not stored.

    Raises
    ------
    rockstudy.core.validation.InputError
        When a field is out of its declared range, or the scan and its resolution do not fit together
        (:func:`~rockstudy.core.relations.check_amplitude_grid`): the one check of a grid, at construction.
    """

    start: float = 0.9
    stop: float = 6.0
    step: float = 0.1
    resolution: float = 0.01
    names: InitVar[dict | None] = None

    def __post_init__(self, names):
        names = names or {}
        check_arguments("AmplitudeGrid", self.__dict__, names)  # each field's type and range (core.quantities)
        validation.check_amplitude_grid(self.start, self.stop, self.step, self.resolution,  # their relations
                                        names=tuple(names.get(f, f"AmplitudeGrid.{f}") for f in GRID_FIELDS))

    def simulations(self) -> int:
        """The most simulations one threshold on this grid may need: the scan's points and the bisection's
        steps (the grid was checked when it was made)."""
        return validation.grid_size(self.start, self.stop, self.step) + validation.bisection_steps(
            self.step, self.resolution)

    def values(self) -> np.ndarray:
        n = int(math.floor((self.stop - self.start) / self.step + 1e-9))
        return np.round(self.start + self.step * np.arange(n + 1), 10)


DEFAULT_FREQUENCY_GRID = {"start": 0.25, "stop": 5.0, "step": 0.1}
"""The study's frequency ratios ω_p/p (``frequency_grid`` of config.yaml). [-]"""


@declares(start="frequency_ratio", stop="frequency_ratio", step="frequency_ratio")
def frequency_grid(start: float = DEFAULT_FREQUENCY_GRID["start"], stop: float = DEFAULT_FREQUENCY_GRID["stop"],
                   step: float = DEFAULT_FREQUENCY_GRID["step"], *, names: dict | None = None) -> np.ndarray:
    """Frequency ratios ω_p/p from ``start`` to ``stop`` (inclusive) in ``step``: the abscissa of an
    overturning spectrum.

    Parameters
    ----------
    start, stop : float
        First and last ω_p/p, 0 < start <= stop <= :data:`~rockstudy.core.validation.MAX_FREQUENCY_RATIO`. [-]
    step : float
        Spacing of the ratios; the grid has at most :data:`~rockstudy.core.validation.MAX_GRID_POINTS`
        points. [-]
    names : dict, optional
        The caller's name of each argument in error messages (``{"step": "--frequency-step"}``); an argument
        missing from it is named as it is here.

    Returns
    -------
    numpy.ndarray
        The ratios, rounded to 10 decimals so that a grid read back from a file compares equal. [-]

    Raises
    ------
    rockstudy.core.validation.InputError
        Naming the argument that is out of range.
    """
    # finite numbers (not bools), 0 < start <= stop <= the largest ratio, at most MAX_GRID_POINTS points: the
    # size is bounded before the grid is made
    names = names or {}
    check_arguments("frequency_grid", {"start": start, "stop": stop, "step": step}, names)
    validation.check_grid("frequency_grid", start, stop, step, high=MAX_FREQUENCY_RATIO,
                          names=tuple(names.get(arg, arg) for arg in ("start", "stop", "step")))
    n = int(math.floor((stop - start) / step + 1e-9))
    return np.round(start + step * np.arange(n + 1), 10)


def _check_call(scenario, grid) -> None:
    """The library's entry points take a Scenario and an AmplitudeGrid (named when not)."""
    if not isinstance(scenario, Scenario):
        raise validation.InputError(f"scenario must be a rockstudy Scenario, got {type(scenario).__name__}")
    if not isinstance(grid, AmplitudeGrid):
        raise validation.InputError(f"grid must be a rockstudy AmplitudeGrid, got {type(grid).__name__}")


def _realisation_list(realisations) -> list[int]:
    """Distinct integer indices >= 0, at most :data:`~rockstudy.core.validation.MAX_REALISATIONS` of them
    (counted before an iterator is drawn further)."""
    if isinstance(realisations, (str, bytes)) or not hasattr(realisations, "__iter__"):
        raise validation.InputError(f"realisations must be a sequence of integers, got {realisations!r}")
    try:
        n, counted = len(realisations), f"{len(realisations)} indices"
    except TypeError:
        realisations = list(itertools.islice(realisations, SIZES["spectrum", "realisations"] + 1))
        n, counted = len(realisations), f"more than {SIZES['spectrum', 'realisations']} indices"
    if n > SIZES["spectrum", "realisations"]:
        validation.fail("realisations", counted,
                        f"at most {SIZES['spectrum', 'realisations']} realisations (the paper uses 100)")
    out = [QUANTITIES["realisation"].check(f"realisations[{i}]", k) for i, k in enumerate(realisations)]
    if len(out) == 0 or len(set(out)) != len(out):
        raise validation.InputError(f"realisations must be distinct integers >= 0, got {out!r}")
    return out


def _reference_outcome(scenario: Scenario, motion: GroundMotion, amplitude_ratio: float, peak: float) -> Outcome:
    """Outcome of one reference-engine run at one amplitude ratio."""
    if amplitude_ratio * peak <= 1.0:
        return Outcome.NO_UPLIFT
    r = scenario.simulate_motion(motion.scaled(amplitude_ratio * scenario.block.uplift_acceleration),
                                 engine="reference")
    if not r.overturned:
        return Outcome.SAFE
    return Outcome.OVERTURNED_AFTER_IMPACT if r.n_impacts else Outcome.OVERTURNED_WITHOUT_IMPACT


@dataclass(frozen=True)
class ThresholdResult:
    """The minimum overturning amplitude ratio at one frequency, as :func:`threshold` finds it.

    Attributes
    ----------
    amplitude_ratio : float or None
        a_min,OVER/(g·tanα): the lowest overturning amplitude ratio found, to ``resolution``
        (None when nothing on the scan overturns). [-]
    last_safe_amplitude_ratio : float
        The highest amplitude ratio found safe below it (the scan's top when nothing overturned). [-]
    max_amplitude_ratio : float
        The scan's top. [-]
    resolution : float
        Bisection resolution. [-]
    frequency_ratio : float
        ω_p/p. [-]
    n_simulations : int
        Runs the scan made.
    n_undetermined : int
        Runs that hit the fast engine's event cap (counted as not overturned).
    energy_ratio, pga_ratio : float
        The noisy record's energy and PGA over the baseline's (1 without noise). [-]
    engine : str
        "fast" or "reference".

    ``result["amplitude_ratio"]`` reads a field as the dict this function returned before;
    :meth:`as_dict` gives all of them (JSON-friendly).
    """

    amplitude_ratio: float | None
    last_safe_amplitude_ratio: float
    max_amplitude_ratio: float
    resolution: float
    frequency_ratio: float
    n_simulations: int
    n_undetermined: int
    energy_ratio: float
    pga_ratio: float
    engine: str

    def as_dict(self) -> dict:
        """The fields as a dict (JSON-friendly: plain floats, ints, str and None)."""
        return asdict(self)

    def __getitem__(self, name: str):
        if name not in {f.name for f in fields(self)}:
            raise KeyError(name)
        return getattr(self, name)


@declares(frequency_ratio="frequency_ratio", realisation="realisation")
def threshold(scenario: Scenario, frequency_ratio: float, *, realisation: int = 0,
              grid: AmplitudeGrid = AmplitudeGrid(), engine: str = "fast",
              energy_bound: bool = True, names: dict | None = None) -> ThresholdResult:
    """Minimum overturning amplitude ratio a_p/(g·tanα) at one frequency ratio: one point of an
    overturning spectrum (§4 of the paper), found by an upward scan of the amplitude grid (every
    lower level shown safe) and a bisection to the grid's resolution.

    Parameters
    ----------
    scenario : Scenario
        The block, anchorage, control, excitation and noise level.
    frequency_ratio : float
        ω_p/p of the excitation (Eq. 23). [-]
    realisation : int, default 0
        The noise realisation (its seed is derived from the scenario's seed and this number).
    grid : AmplitudeGrid, optional
        The amplitudes a_p/(g·tanα) scanned and the bisection's resolution. [-]
    engine : {"fast", "reference"}, default "fast"
        The compiled engine, or the pure-Python reference (slow; for checks).
    energy_bound : bool, default True
        Fast engine: end each run once it provably cannot overturn any more (docs/engine.md,
        "Early stops"); it
        never changes an outcome, only the time spent (False: integrate every run to rest or the
        time limit).
    names : dict, optional
        The caller's name of ``frequency_ratio``, ``realisation`` and the inputs of the time span in error
        messages (``{"frequency_ratio": "--frequency-ratio"}``, :func:`rockstudy.analysis.scenario.span_names`).

    Returns
    -------
    ThresholdResult
        ``amplitude_ratio`` (None when nothing on the grid overturns), ``last_safe_amplitude_ratio``,
        ``n_simulations``, the bound scanned, and the noise record's energy and PGA ratios.

    Raises
    ------
    rockstudy.core.validation.InputError
        When an argument is out of its declared range.
    """
    _check_call(scenario, grid)
    checked = check_arguments("threshold", {"frequency_ratio": frequency_ratio, "realisation": realisation}, names)
    frequency_ratio, realisation = checked["frequency_ratio"], checked["realisation"]
    scenario.check_span([frequency_ratio], **span_names(names))
    values = grid.values()
    case = scenario.kernel_case(frequency_ratio, realisation, energy_bound=energy_bound)
    if engine == "fast":
        thr, lo, n_sim, n_und = kernel.threshold_kernel(
            case.parameters, kernel.writable(case.samples), kernel.writable(case.vertical), values,
            float(grid.resolution), float(case.peak))
    elif engine == "reference":
        # the same scan as the fast engine's (kernel.threshold_kernel), driven from Python
        motion, _ = scenario.motion(frequency_ratio, 1.0, realisation)
        state, done, n_sim, lower = kernel.scan_start(), False, 0, 1.0 / case.peak
        while not done:
            o = _reference_outcome(scenario, motion, float(kernel.scan_amplitude(state, values)), case.peak)
            n_sim += o != Outcome.NO_UPLIFT
            done = kernel.scan_update(state, values, grid.resolution, lower, o.overturned)
        thr, lo, n_und = state[kernel.S_HI], state[kernel.S_LO], 0
    else:
        raise ValueError(f"engine must be 'fast' or 'reference', got {engine!r}")
    return ThresholdResult(
        amplitude_ratio=None if not np.isfinite(thr) else float(thr),
        last_safe_amplitude_ratio=float(lo),
        max_amplitude_ratio=float(values[-1]),
        resolution=float(grid.resolution),
        frequency_ratio=float(frequency_ratio),
        n_simulations=int(n_sim),
        n_undetermined=int(n_und),
        energy_ratio=float(case.energy_ratio),
        pga_ratio=float(case.pga_ratio),
        engine=engine,
    )


def _cases(scenario: Scenario, frequency_ratios, realisations, energy_bound: bool = True):
    """Parameter rows and concatenated records for every (realisation, frequency) case."""
    rows, recs, peaks, e_ratio, p_ratio = [], [], [], [], []
    for k in realisations:
        for f in frequency_ratios:
            case = scenario.kernel_case(float(f), int(k), energy_bound=energy_bound)
            rows.append(case.parameters)
            recs.append(case.samples)
            peaks.append(case.peak)
            e_ratio.append(case.energy_ratio)
            p_ratio.append(case.pga_ratio)
    lengths = np.array([len(r) for r in recs], dtype=np.int64)
    offsets = np.concatenate([[0], np.cumsum(lengths)[:-1]]).astype(np.int64)
    flat = np.concatenate(recs) if lengths.sum() else np.zeros(0)
    return (np.array(rows), flat, offsets, lengths, np.array(peaks), np.array(e_ratio), np.array(p_ratio))


SMALL_MAP_RUNS = 20_000
"""A map of at most this many runs (cases × amplitudes) on one thread is run by one call of the compiled
``outcome_kernel`` per grid point (:func:`_outcome_calls`), the function the record scans call: the batch
loop ``outcome_serial`` then need not be compiled (2 s of CPU on an empty cache), for 5–25 µs more a run
(each call makes the case's early-stop data again). The same code runs either way, so the outcomes are
the same."""


def _threshold_calls(Pm, recs, rec_off, rec_len, vert, grid, resolution, peaks):
    """``kernel.threshold_batch``'s results on one thread: one call of the compiled ``kernel.threshold_kernel``
    per case, the function the record scans call, so that no batch loop is compiled for it (1 s of CPU on an
    empty cache) for about 1 µs a case. The same code runs either way, so the thresholds are the same."""
    n = len(Pm)
    out, low = np.empty(n), np.empty(n)
    nsim, nund = np.zeros(n, dtype=np.int64), np.zeros(n, dtype=np.int64)
    for i in range(n):
        rec = recs[rec_off[i]:rec_off[i] + rec_len[i]]
        out[i], low[i], nsim[i], nund[i] = kernel.threshold_kernel(Pm[i], rec, vert, grid, resolution, peaks[i])
    return out, low, nsim, nund


def _outcome_calls(Pm, recs, rec_off, rec_len, vert, grid, peaks):
    """``kernel.outcome_serial``'s outcomes, one call of ``kernel.outcome_kernel`` per case and amplitude."""
    out = np.zeros((len(Pm), len(grid)), dtype=np.int8)
    for i in range(len(Pm)):
        rec = recs[rec_off[i]:rec_off[i] + rec_len[i]]
        for j in range(len(grid)):
            out[i, j] = kernel.outcome_kernel(Pm[i], rec, vert, grid[j], peaks[i])
    return out


PROGRESS_BATCHES = 100
"""Batches of a run that reports to a progress bar (``progress=``): the bar moves in steps of about 1 %."""


def _run_chunked(fn, n_cases: int, label: str, n_chunks: int, progress=None):
    """Run ``fn(sl)`` over slices of the cases, logging progress and the time left after each of ``n_chunks``
    batches, or, with ``progress``, calling ``progress(done, n_cases, label)`` after each of about
    :data:`PROGRESS_BATCHES` batches instead. The cases are independent, so the batches do not change the
    results."""
    if progress is not None:
        n_chunks = max(n_chunks, PROGRESS_BATCHES)
        progress(0, n_cases, label)
    t0 = time.perf_counter()
    bounds = np.linspace(0, n_cases, min(n_chunks, n_cases) + 1).astype(int)
    parts = []
    for i in range(len(bounds) - 1):
        with interruptible():  # Ctrl-C in the compiled cases: a KeyboardInterrupt, not a SystemError
            parts.append(fn(slice(bounds[i], bounds[i + 1])))
        done = bounds[i + 1]
        if progress is not None:
            progress(int(done), n_cases, label)
            continue
        elapsed = time.perf_counter() - t0
        eta = elapsed / done * (n_cases - done)
        log.info("%s: %d/%d cases (%.0f%%), %.1f s elapsed, about %.1f s left",
                 label, done, n_cases, 100 * done / n_cases, elapsed, eta)
    return parts


@declares(sizes={"frequency_ratios": MAX_GRID_POINTS, "realisations": MAX_REALISATIONS},
          frequency_ratios="frequency_ratio", realisations="realisation")
def spectrum(scenario: Scenario, frequency_ratios, *, realisations=(0,), grid: AmplitudeGrid = AmplitudeGrid(),
             with_map: bool = False, progress_chunks: int = 10, energy_bound: bool = True,
             progress=None) -> xr.Dataset:
    """Overturning spectrum: the threshold at each frequency for each noise realisation.

    Parameters
    ----------
    scenario : Scenario
        Block, anchorage, strategy, excitation and noise of the runs.
    frequency_ratios : array_like
        ω_p/p values. [-]
    realisations : sequence of int
        Noise realisation indices (ignored beyond the first when ``noise_level`` = 0).
    grid : AmplitudeGrid
        Amplitude ratios of the upward scan and the resolution of the threshold.
    with_map : bool
        Also compute the outcome at every (frequency, amplitude) grid point.
    progress_chunks : int, default 10
        Number of batches the runs are split into, each logging its progress and the time left.
    energy_bound : bool
        End runs that provably cannot overturn any more (see :func:`threshold`).
    progress : callable, optional
        ``progress(done, total, label)``, called as the cases are done (the command line's progress bar at a
        terminal), instead of the log lines; None: the log lines (a workflow job's log).

    Returns
    -------
    xarray.Dataset
        ``threshold_realisation`` (realisation, frequency_ratio); the paper's aggregate
        ``threshold`` (the lowest over realisations) with ``threshold_mean`` and ``threshold_std``;
        ``last_safe``, ``n_simulations``, ``energy_ratio``, ``pga_ratio``; and ``outcome`` on
        request. NaN thresholds mean "no overturning up to the grid's upper bound".
    """
    _check_call(scenario, grid)
    try:  # at most one value past the limit is drawn from an iterator
        items = list(itertools.islice(iter(frequency_ratios), SIZES["spectrum", "frequency_ratios"] + 1))
    except TypeError:
        raise validation.InputError(
            f"frequency_ratios must be a 1-D list of numbers, got {type(frequency_ratios).__name__}") from None
    if isinstance(frequency_ratios, (str, bytes)) or not 1 <= len(items) <= SIZES["spectrum", "frequency_ratios"]:
        validation.fail("frequency_ratios", f"{len(items)} values" if len(items) else "no value",
                        f"a 1-D list of 1 to {SIZES['spectrum', 'frequency_ratios']} frequency ratios")
    freqs = np.array([QUANTITIES["frequency_ratio"].check(f"frequency_ratios[{i}]", f) for i, f in enumerate(items)])
    realisations = _realisation_list(realisations)
    if scenario.noise_level == 0 and len(realisations) > 1:
        realisations = realisations[:1]  # without noise every realisation is the same record
    sims = grid.simulations()  # the grid was checked when it was made
    scenario.check_span([freqs.min(), freqs.max()], frequency_name="frequency_ratios")
    n_real = len(realisations)
    validation.check_workload("realisations", n_real, n_real * len(freqs), sims * (2 if with_map else 1),
                     scenario.record_bytes(freqs, n_real))
    values = grid.values()
    Pm, recs, off, lens, peaks, e_ratio, p_ratio = _cases(scenario, freqs, realisations, energy_bound)
    n = len(Pm)
    label = f"spectrum {scenario.control.strategy} noise={scenario.noise_level:g} Ts={scenario.control.sampling_time:g}"
    t0 = time.perf_counter()

    # one thread (a workflow job, --threads 1): without numba's parallel machinery
    serial = numba.get_num_threads() == 1
    thresholds = _threshold_calls if serial else kernel.threshold_batch
    outcomes = kernel.outcome_batch
    if serial:
        outcomes = _outcome_calls if n * len(values) <= SMALL_MAP_RUNS else kernel.outcome_serial

    def run(sl):
        return thresholds(Pm[sl], recs, off[sl], lens[sl], np.zeros(0), values, grid.resolution, peaks[sl])

    parts = _run_chunked(run, n, label, progress_chunks, progress)
    thr = np.concatenate([p[0] for p in parts])
    low = np.concatenate([p[1] for p in parts])
    nsim = np.concatenate([p[2] for p in parts])
    nund = np.concatenate([p[3] for p in parts])
    if nund.any():
        log.warning("%s: %d run(s) hit the engine's event cap and were counted as not overturned "
                    "(see the n_undetermined variable)", label, int(nund.sum()))
    shape = (len(realisations), len(freqs))
    ds = spectrum_dataset(scenario, freqs, realisations, thr.reshape(shape), low.reshape(shape),
                          nsim.reshape(shape), e_ratio.reshape(shape), p_ratio.reshape(shape), grid,
                          n_undetermined=nund.reshape(shape))
    if with_map:
        def run_map(sl):
            return outcomes(Pm[sl], recs, off[sl], lens[sl], np.zeros(0), values, peaks[sl])
        out = np.concatenate(_run_chunked(run_map, n, label + " map", progress_chunks, progress))
        ds["outcome"] = (("realisation", "frequency_ratio", "amplitude_ratio"), out.reshape(shape + (len(values),)),
                         {"long_name": "outcome of the simulation at each grid point",
                          "flag_values": np.arange(len(OUTCOME_MEANINGS), dtype=np.int8),
                          "flag_meanings": " ".join(OUTCOME_MEANINGS)})
        ds = ds.assign_coords(amplitude_ratio=("amplitude_ratio", values,
                                               {"units": "1", "long_name": "amplitude ratio a_p/(g tan(alpha))"}))
    ds.attrs["compute_time_s"] = time.perf_counter() - t0
    return ds


def spectrum_dataset(scenario, freqs, realisations, thr, low, nsim, e_ratio, p_ratio, grid,
                     n_undetermined=None) -> xr.Dataset:
    """Assemble the labelled spectrum Dataset (one strategy, noise level, T_s and Δτ).

    Parameters
    ----------
    scenario : Scenario
        The scenario of the runs (coordinates and global attributes).
    freqs : array_like, shape (frequency_ratio,)
        ω_p/p values. [-]
    realisations : sequence of int
        Noise realisation indices.
    thr, low : ndarray, shape (realisation, frequency_ratio)
        Threshold amplitude ratio (NaN: none up to the scan's top) and the highest ratio found safe below
        it. [-]
    nsim : ndarray of int, shape (realisation, frequency_ratio)
        Simulations run for each threshold.
    e_ratio, p_ratio : ndarray, shape (realisation, frequency_ratio)
        Energy and PGA of each noisy record over its baseline's. [-]
    grid : AmplitudeGrid
        The amplitude scan, written as ``grid_amplitude_*`` attributes.
    n_undetermined : ndarray of int or None, default None
        Runs that hit the engine's event cap; None: zeros.
    """
    dims = ("realisation", "frequency_ratio")
    if n_undetermined is None:
        n_undetermined = np.zeros(np.shape(thr), dtype=np.int64)
    finite = np.isfinite(thr)
    count = finite.sum(axis=0)
    agg = np.where(count > 0, np.min(np.where(finite, thr, np.inf), axis=0), np.nan)
    safe_count = np.maximum(count, 1)
    mean = np.where(count > 0, np.where(finite, thr, 0.0).sum(axis=0) / safe_count, np.nan)
    var = np.where(finite, (thr - mean) ** 2, 0.0).sum(axis=0) / safe_count
    std = np.where(count > 0, np.sqrt(var), np.nan)
    amp = {"units": "1", "long_name": "minimum overturning amplitude ratio a_min,OVER/(g tan(alpha))"}
    ds = xr.Dataset(
        data_vars={
            "threshold": ("frequency_ratio", agg, {**amp, "description":
                          "lowest threshold over the realisations (the paper's a_min,OVER); NaN: none below the "
                          "scan's upper bound"}),
            "threshold_mean": ("frequency_ratio", mean, {**amp, "description": "mean over realisations (NaN ignored)"}),
            "threshold_std": ("frequency_ratio", std, {**amp, "description": "std over realisations (NaN ignored)"}),
            "threshold_realisation": (dims, thr, {**amp, "description": "threshold of each noise realisation"}),
            "last_safe": (dims, low, {"units": "1",
                                      "long_name": "highest amplitude ratio found safe below the threshold"}),
            "n_simulations": (dims, nsim, {"units": "1", "long_name": "simulations run for the threshold"}),
            "n_undetermined": (dims, n_undetermined, {
                "units": "1", "long_name": "runs that hit the fast engine's event cap",
                "description": "counted as not overturned by the scan; 0 expected"}),
            "energy_ratio": (dims, e_ratio, {"units": "1", "long_name": "noisy record energy / baseline energy"}),
            "pga_ratio": (dims, p_ratio, {"units": "1", "long_name": "noisy record PGA / baseline PGA"}),
        },
        coords={
            "frequency_ratio": ("frequency_ratio", np.asarray(freqs, float),
                                {"units": "1", "long_name": "excitation frequency ratio omega_p/p"}),
            "excitation_frequency": ("frequency_ratio", np.asarray(freqs, float) * scenario.block.p,
                                     {"units": "rad/s", "long_name": "excitation circular frequency omega_p"}),
            "realisation": ("realisation", np.asarray(realisations, dtype=np.int64),
                            {"long_name": "noise realisation index k"}),
            "strategy": ((), scenario.control.strategy, {"long_name": "control strategy"}),
            "noise_level": ((), float(scenario.noise_level),
                            {"units": "1", "long_name": "noise energy / baseline energy"}),
            "sampling_time": ((), float(scenario.control.sampling_time),
                              {"units": "s", "long_name": "controller sampling time T_s (0: continuous)"}),
            "delay": ((), float(scenario.control.delay), {"units": "s", "long_name": "actuation delay"}),
        },
        attrs={
            "title": f"Overturning spectrum, {scenario.control.strategy}, {scenario.excitation} excitation",
            "rockstudy_version": __version__,
            "paper": PAPER,
            "paper_equations": PAPER_EQUATIONS,
            "grid_amplitude_start": grid.start, "grid_amplitude_stop": grid.stop,
            "grid_amplitude_step": grid.step, "grid_amplitude_resolution": grid.resolution,
            "a_max0_ratio": 1.0 / math.tan(scenario.block.alpha),
            "a_max0_ratio_note": "a_max,0 = g expressed as an amplitude ratio, 1/tan(alpha)",
            **scenario.to_attrs(),
        },
    )
    return ds


def convergence(ds: xr.Dataset) -> xr.DataArray:
    """Aggregate threshold (lowest over the first N realisations) for N = 1 … n (Fig. 6a).

    Parameters
    ----------
    ds : xarray.Dataset
        A spectrum of :func:`spectrum` (its ``threshold_realisation``).
    """
    thr = ds["threshold_realisation"].values
    filled = np.where(np.isnan(thr), np.inf, thr)
    run = np.minimum.accumulate(filled, axis=0)
    run = np.where(np.isinf(run), np.nan, run)
    n = np.arange(1, thr.shape[0] + 1)
    return xr.DataArray(run, dims=("n_realisations", "frequency_ratio"),
                        coords={"n_realisations": ("n_realisations", n, {"long_name": "number of realisations N"}),
                                "frequency_ratio": ds["frequency_ratio"]},
                        name="threshold_convergence",
                        attrs={"units": "1", "long_name": "lowest threshold over the first N realisations"})
