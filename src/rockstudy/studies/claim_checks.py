"""The paper's checkable statements (§5 and the Conclusions), each a plain function of a run's tables and
spectra that returns a :class:`ClaimResult`; :mod:`rockstudy.studies.claims` evaluates them all and writes
the verdicts.

Inputs are the datasets of :mod:`rockstudy.studies.study`: Table 1 (``j_os`` over ``reference`` ×
``strategy`` × ``noise_level``), the timing tables (``j_os`` over ``reference`` × ``strategy`` ×
``sampling_time`` or ``delay``), the convergence dataset of Fig. 6a, and the gathered spectra. J_OS values
are in percent; thresholds are ratios a_p/(g·tanα).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from rockstudy.analysis.utility_index import utility_index

PAPER_TABLE1 = {
    ("no_noise", "FS"): (-2.01, -5.43, -6.28),
    ("no_noise", "CS01"): (-2.88, -1.61, -0.26),
    ("no_noise", "CS02"): (+1.18, +2.13, +8.09),
    ("fs_same_noise", "CS01"): (+28.02, +30.51, +32.44),
    ("fs_same_noise", "CS02"): (+16.55, +19.65, +23.52),
}
"""The paper's Table 1, J_OS [%] at R001, R005, R010, by (reference, strategy)."""
PAPER_LEVELS = ("R001", "R005", "R010")
"""Noise levels of the paper's Table 1 (noise energy 1 %, 5 %, 10 % of the baseline's)."""

APPRECIABLE = 2.0
"""A J_OS change of at least this many points [%] is "appreciable" / "significant" (§5.2)."""
CONVERGED = 1.0
"""40 realisations are "enough" when the 10 last move J_OS of the aggregate by less than this [%]."""
CONVERGENCE_FROM = 30
"""The aggregate at N = 40 is compared with the one at N = CONVERGENCE_FROM."""
RANGE_SLACK = 1.0
"""The Conclusions' ranges ("+28 % to +32 %") are read as whole percent (truncated): low <= J < high + 1 [%]."""


@dataclass(frozen=True)
class ClaimResult:
    """One evaluated statement.

    Parameters
    ----------
    key : str
        Short identifier, e.g. ``"fs_negative"``.
    section : str
        Where the paper says it (``"5.1"``, ``"5.2"``, ``"6"``).
    statement : str
        The paper's words (quoted or closely paraphrased).
    definition : str
        What we check, with the thresholds used.
    evidence : str
        The numbers behind the verdict.
    passed : bool or None
        The verdict; None when the run lacks the data.
    paper_passed : bool or None
        The same check on the paper's own Table 1, when it applies.
    """

    key: str
    section: str
    statement: str
    definition: str
    evidence: str
    passed: bool | None
    paper_passed: bool | None = None

    def __post_init__(self):
        for name in ("key", "section", "statement", "definition", "evidence"):
            if not isinstance(getattr(self, name), str):
                raise ValueError(f"ClaimResult.{name} must be a string, got {getattr(self, name)!r}")
        for name in ("passed", "paper_passed"):
            value = getattr(self, name)
            if value is not None and not isinstance(value, (bool, np.bool_)):
                raise ValueError(f"ClaimResult.{name} must be True, False or None, got {value!r}")
            object.__setattr__(self, name, None if value is None else bool(value))

    @property
    def verdict(self) -> str:
        """"PASS", "FAIL" or "n/a"."""
        return "n/a" if self.passed is None else ("PASS" if self.passed else "FAIL")


# --- helpers -------------------------------------------------------------------------------------
def _fmt(values) -> str:
    return ", ".join(f"{v:+.2f}" for v in values)


def _row(table: xr.Dataset | None, reference: str, strategy: str, levels=PAPER_LEVELS):
    """J_OS [%] of one Table 1 row at ``levels``; None when any cell is missing or NaN."""
    if table is None:
        return None
    try:
        values = [float(table["j_os"].sel(reference=reference, strategy=strategy, noise_level=lv)) for lv in levels]
    except KeyError:
        return None
    return None if any(math.isnan(v) for v in values) else values


def _paper_row(reference: str, strategy: str):
    return list(PAPER_TABLE1[(reference, strategy)])


def _decreasing(values) -> bool:
    return all(b < a for a, b in zip(values, values[1:]))


def _increasing(values) -> bool:
    return all(b > a for a, b in zip(values, values[1:]))


def _timing(table: xr.Dataset | None, reference: str, strategy: str, variable: str):
    """{value [s]: J_OS [%]} of one timing-table row, or None."""
    if table is None or variable not in table.dims:
        return None
    try:
        row = table["j_os"].sel(reference=reference, strategy=strategy)
    except KeyError:
        return None
    return {float(v): float(j) for v, j in zip(row[variable].values, row.values)}


def total_variation(thresholds, cap: float) -> float:
    """Total variation Σ|a_{i+1} − a_i| of a threshold curve over the frequency grid. [-]

    Parameters
    ----------
    thresholds : array_like
        Threshold a_p/(g·tanα) at each frequency of the grid, in order. [-]
    cap : float
        The bound that NaN (no overturning up to the scan bound) and larger values count as, so a spectrum
        that leaves the scan range is not rewarded or punished beyond the bound. [-]
    """
    a = np.asarray(thresholds, dtype=float)
    a = np.where(np.isnan(a) | (a > cap), cap, a)
    return float(np.sum(np.abs(np.diff(a))))


# --- Table 1 claims ------------------------------------------------------------------------------
def claim_fs_negative(table) -> ClaimResult:
    """§5.1: noise makes the free-standing block less stable, J_OS of FS against FS without noise < 0 at
    R001, R005 and R010.

    Parameters
    ----------
    table : xarray.Dataset or None
        Table 1 (:func:`rockstudy.studies.tables.table1`); None or a missing cell: not evaluated.
    """
    ours, paper = _row(table, "no_noise", "FS"), _paper_row("no_noise", "FS")
    return ClaimResult(
        "fs_negative", "5.1", "Noise makes the free-standing block less stable: J_OS of FS against no noise < 0.",
        "J_OS(FS vs FS without noise) < 0 at R001, R005 and R010.",
        "n/a (Table 1 incomplete)" if ours is None else f"ours {_fmt(ours)} %; paper {_fmt(paper)} %",
        None if ours is None else all(v < 0 for v in ours), all(v < 0 for v in paper))


def claim_fs_falls(table) -> ClaimResult:
    """§5.1: J_OS of the free-standing block against no noise decreases as the noise level grows.

    Parameters
    ----------
    table : xarray.Dataset or None
        Table 1 (:func:`rockstudy.studies.tables.table1`); None or a missing cell: not evaluated.
    """
    ours, paper = _row(table, "no_noise", "FS"), _paper_row("no_noise", "FS")
    return ClaimResult(
        "fs_falls_with_noise", "5.1", "\"The value of J_OS of the free standing block decreases with increasing the "
        "level of noise.\"", "J_OS(FS vs no noise) strictly decreasing from R001 to R005 to R010.",
        "n/a (Table 1 incomplete)" if ours is None else f"ours {_fmt(ours)} %; paper {_fmt(paper)} %",
        None if ours is None else _decreasing(ours), _decreasing(paper))


def claim_controlled_rises(table) -> ClaimResult:
    """§5.1: J_OS of the controlled blocks (CS01, CS02) against no noise grows with the noise level.

    Parameters
    ----------
    table : xarray.Dataset or None
        Table 1 (:func:`rockstudy.studies.tables.table1`); None or a missing cell: not evaluated.
    """
    rows = {s: _row(table, "no_noise", s) for s in ("CS01", "CS02")}
    paper = {s: _paper_row("no_noise", s) for s in ("CS01", "CS02")}
    ok = None if any(v is None for v in rows.values()) else all(_increasing(v) for v in rows.values())
    evidence = "n/a (Table 1 incomplete)" if ok is None else "; ".join(
        f"{s}: ours {_fmt(rows[s])} %, paper {_fmt(paper[s])} %" for s in rows)
    return ClaimResult(
        "controlled_rises_with_noise", "5.1", "\"... whilst the opposite happens for the controlled body\" (J_OS "
        "against no noise grows with the noise level).",
        "J_OS(CS01 vs no noise) and J_OS(CS02 vs no noise) strictly increasing from R001 to R010.",
        evidence, ok, all(_increasing(v) for v in paper.values()))


def claim_controlled_less_sensitive(table) -> ClaimResult:
    """§5.1: noise moves the threshold of the controlled blocks less than that of the free-standing block,
    ``|J_OS(S vs no noise)| < |J_OS(FS vs no noise)|`` for S = CS01, CS02 at every level.

    Parameters
    ----------
    table : xarray.Dataset or None
        Table 1 (:func:`rockstudy.studies.tables.table1`); None or a missing cell: not evaluated.
    """
    fs = _row(table, "no_noise", "FS")
    rows = {s: _row(table, "no_noise", s) for s in ("CS01", "CS02")}

    def check(fs_row, row_map):
        return all(abs(row_map[s][i]) < abs(fs_row[i]) for s in row_map for i in range(len(fs_row)))

    ok = None if fs is None or any(v is None for v in rows.values()) else check(fs, rows)
    paper = check(_paper_row("no_noise", "FS"), {s: _paper_row("no_noise", s) for s in rows})
    evidence = "n/a (Table 1 incomplete)" if ok is None else (
        f"|J_OS| vs no noise, FS {_fmt(np.abs(fs))}; CS01 {_fmt(np.abs(rows['CS01']))}; "
        f"CS02 {_fmt(np.abs(rows['CS02']))} %")
    return ClaimResult(
        "controlled_less_sensitive", "5.1", "\"The discrepancy between the a_min,OVER of the contaminated and pure "
        "... excitations decreases when moving from the uncontrolled free standing block to the controlled one.\"",
        "|J_OS(S vs no noise)| < |J_OS(FS vs no noise)| for S = CS01, CS02 at every level.", evidence, ok, paper)


def claim_both_beat_fs(table) -> ClaimResult:
    """§5.1 and §6: both controlled blocks are more stable than the free-standing block at every noise
    level (J_OS against FS at the same noise > 0).

    Parameters
    ----------
    table : xarray.Dataset or None
        Table 1 (:func:`rockstudy.studies.tables.table1`); None or a missing cell: not evaluated.
    """
    rows = {s: _row(table, "fs_same_noise", s) for s in ("CS01", "CS02")}
    ok = None if any(v is None for v in rows.values()) else all(v > 0 for r in rows.values() for v in r)
    evidence = "n/a (Table 1 incomplete)" if ok is None else "; ".join(
        f"{s} vs FS: {_fmt(r)} %" for s, r in rows.items())
    return ClaimResult(
        "both_beat_fs", "5.1 / 6", "Both controlled blocks are more stable than the free-standing block at every "
        "noise level.", "J_OS(CS01 vs FS) > 0 and J_OS(CS02 vs FS) > 0 at R001, R005, R010 (same noise).",
        evidence, ok, True)


def claim_cs01_beats_cs02(table) -> ClaimResult:
    """§5.1 and §6: the feedback strategy CS01 is more stable than the feedback-feedforward strategy CS02
    (J_OS against FS larger at every level).

    Parameters
    ----------
    table : xarray.Dataset or None
        Table 1 (:func:`rockstudy.studies.tables.table1`); None or a missing cell: not evaluated.
    """
    c1, c2 = _row(table, "fs_same_noise", "CS01"), _row(table, "fs_same_noise", "CS02")
    ok = None if c1 is None or c2 is None else all(a > b for a, b in zip(c1, c2))
    return ClaimResult(
        "cs01_beats_cs02", "5.1 / 6", "\"The block controlled through the feedback strategy (CS01) results to be more "
        "stable than the block controlled by the feedback-feedforward strategy (CS02).\"",
        "J_OS(CS01 vs FS) > J_OS(CS02 vs FS) at every level.",
        "n/a (Table 1 incomplete)" if ok is None else f"CS01 {_fmt(c1)} %; CS02 {_fmt(c2)} %", ok, True)


def claim_gap_shrinks(table) -> ClaimResult:
    """§5.1: the gap between CS01 and CS02 (J_OS against FS) shrinks as the noise level falls.

    Parameters
    ----------
    table : xarray.Dataset or None
        Table 1 (:func:`rockstudy.studies.tables.table1`); None or a missing cell: not evaluated.
    """
    c1, c2 = _row(table, "fs_same_noise", "CS01"), _row(table, "fs_same_noise", "CS02")
    p1, p2 = _paper_row("fs_same_noise", "CS01"), _paper_row("fs_same_noise", "CS02")
    paper_gap = [a - b for a, b in zip(p1, p2)]
    ok, evidence = None, "n/a (Table 1 incomplete)"
    if c1 is not None and c2 is not None:
        gap = [a - b for a, b in zip(c1, c2)]
        ok = _increasing(gap)
        evidence = f"gap CS01 - CS02 vs FS at R001, R005, R010: ours {_fmt(gap)}; paper {_fmt(paper_gap)} points"
    return ClaimResult(
        "gap_shrinks_as_noise_falls", "5.1", "\"Reducing the level of noise, the discrepancy in the performances of "
        "the two control strategies decreases.\"",
        "J_OS(CS01 vs FS) - J_OS(CS02 vs FS) strictly smaller at lower noise: gap(R001) < gap(R005) < gap(R010).",
        evidence, ok, _increasing(paper_gap))


def _range_claim(table, strategy, low, high) -> ClaimResult:
    row = _row(table, "fs_same_noise", strategy)
    lo, hi = low, high + RANGE_SLACK
    paper = _paper_row("fs_same_noise", strategy)
    return ClaimResult(
        f"{strategy.lower()}_range", "6", f"\"The utility index for law {strategy} was seen to be in the range "
        f"+{low:g}% to +{high:g}% for noise up to the 10%.\"",
        f"every J_OS({strategy} vs FS) at R001-R010 in [{lo:g}, {hi:g}) % (the stated range in whole percent, "
        "as the paper's +23.52 % is \"+23 %\").",
        "n/a (Table 1 incomplete)" if row is None else f"ours {_fmt(row)} %; paper {_fmt(paper)} %",
        None if row is None else all(lo <= v < hi for v in row), all(lo <= v < hi for v in paper))


# --- convergence, smoothing ----------------------------------------------------------------------
def claim_forty_enough(conv: xr.Dataset | None, a_max0_ratio: float) -> ClaimResult:
    """§5.1: about 40 noise realisations give a stable aggregate threshold (the convergence study of Fig. 6a,
    N = 40 against N = :data:`CONVERGENCE_FROM`, within :data:`CONVERGED`).

    Parameters
    ----------
    conv : xarray.Dataset or None
        The convergence dataset (:func:`rockstudy.studies.datasets.convergence_dataset`):
        ``threshold_convergence`` over ``n_realisations``; None or fewer than 40 realisations: not evaluated.
    a_max0_ratio : float
        a_max,0 as an amplitude ratio a_p/(g·tanα), as in Table 1. [-]
    """
    statement = ("\"The minimum number of contaminated signals to be taken into account to define a stable "
                 "a_min,OVER was in the range of 40.\"")
    definition = (f"the aggregate threshold of the convergence study (Fig. 6a) at N = 40 differs from the one at "
                  f"N = {CONVERGENCE_FROM} by |J_OS(N=40 vs N={CONVERGENCE_FROM})| < {CONVERGED:g} % (a_max,0 as in "
                  "Table 1).")
    if conv is None or "threshold_convergence" not in conv or conv.sizes.get("n_realisations", 0) < 40:
        return ClaimResult("forty_realisations_enough", "5.1", statement, definition,
                           "n/a (fewer than 40 realisations in the run)", None)
    run = conv["threshold_convergence"]
    a40, a30 = run.sel(n_realisations=40).values, run.sel(n_realisations=CONVERGENCE_FROM).values
    j, _ = utility_index(a40, a30, a_max0_ratio)
    both = np.isfinite(a40) & np.isfinite(a30)
    moved = int(np.count_nonzero(both & (a40 < a30)))
    rel = float(np.nanmax(np.where(both, (a30 - a40) / a30, np.nan))) if both.any() else 0.0
    strategy = conv["strategy"].item() if "strategy" in conv.coords else "?"
    return ClaimResult(
        "forty_realisations_enough", "5.1", statement, definition,
        f"{strategy}: J_OS(N=40 vs N={CONVERGENCE_FROM}) = {j:+.2f} %; the last 10 realisations lower the threshold "
        f"at {moved} of {len(a40)} frequencies, by at most {100 * rel:.1f} %", abs(j) < CONVERGED)


def claim_noise_smooths(spectra: dict, levels: dict, cap: float) -> ClaimResult:
    """§5.1: noise smooths the threshold curve of the controlled blocks: its :func:`total_variation` is
    smaller at every noisy level than without noise, for CS01 and CS02.

    Parameters
    ----------
    spectra : dict
        (strategy, level name) -> aggregate threshold over the frequency grid, for CS01 and CS02 at every
        level; a missing one: not evaluated. [-]
    levels : dict
        Level name -> noise level; the level equal to 0 is the one without noise. [-]
    cap : float
        Threshold cap of :func:`total_variation`. [-]
    """
    statement = ("\"In the presence of noise a_min,OVER of the controlled block becomes more smoothed and spikes tend "
                 "to disappear.\"")
    definition = ("total variation TV = sum |a(w_i+1) - a(w_i)| of the aggregate threshold over the frequency grid "
                  f"(NaN and values above {cap:g} counted as {cap:g}) is smaller at every noisy level than without "
                  "noise, for CS01 and CS02.")
    free = [name for name, v in levels.items() if v == 0]
    noisy = [name for name, v in levels.items() if v > 0]
    parts, ok = [], True
    for s in ("CS01", "CS02"):
        if not free or (s, free[0]) not in spectra or not all((s, lv) in spectra for lv in noisy):
            return ClaimResult("noise_smooths_controlled", "5.1", statement, definition,
                               f"n/a ({s} spectra missing)", None)
        tv0 = total_variation(spectra[(s, free[0])], cap)
        tvs = [total_variation(spectra[(s, lv)], cap) for lv in noisy]
        ok = ok and all(tv < tv0 for tv in tvs)
        parts.append(f"{s}: TV {tv0:.2f} without noise; " + ", ".join(f"{lv} {tv:.2f}" for lv, tv in zip(noisy, tvs)))
    return ClaimResult("noise_smooths_controlled", "5.1", statement, definition, "; ".join(parts), ok)


# --- timing claims -------------------------------------------------------------------------------
def claim_cs01_sampling(sampling: xr.Dataset | None) -> ClaimResult:
    """§5.2: sampling changes CS01 appreciably (by :data:`APPRECIABLE` or more) only at the largest sampling
    time, 0.2 s.

    Parameters
    ----------
    sampling : xarray.Dataset or None
        The sampling-time table (:func:`rockstudy.studies.tables.timing_table` over ``sampling_time``);
        None or no T_s = 0.2 s: not evaluated.
    """
    row = _timing(sampling, "continuous_same_noise", "CS01", "sampling_time")
    statement = ("\"The feedback strategy CS01 ... appreciable difference was found only for the largest sampling "
                 "time of 0.20 s.\"")
    definition = (f"|J_OS(CS01 sampled vs continuous)| < {APPRECIABLE:g} % for every T_s < 0.2 s of the sweep, and "
                  f">= {APPRECIABLE:g} % at T_s = 0.2 s.")
    if row is None or not any(math.isclose(t, 0.2) for t in row):
        return ClaimResult("cs01_sampling_only_at_0.2s", "5.2", statement, definition, "n/a (no T_s = 0.2 s)", None)
    small = all(abs(j) < APPRECIABLE for t, j in row.items() if t < 0.2 - 1e-9)
    big = abs(row[min(row, key=lambda t: abs(t - 0.2))]) >= APPRECIABLE
    return ClaimResult("cs01_sampling_only_at_0.2s", "5.2", statement, definition,
                       "CS01 vs continuous: " + ", ".join(f"T_s={t:g} s {j:+.2f} %" for t, j in row.items()),
                       small and big)


def claim_cs02_sampling(sampling: xr.Dataset | None) -> ClaimResult:
    """§5.2: CS02 deteriorates at a sampling time of 0.1 s: its J_OS against continuous control drops by
    :data:`APPRECIABLE` or more.

    Parameters
    ----------
    sampling : xarray.Dataset or None
        The sampling-time table (:func:`rockstudy.studies.tables.timing_table` over ``sampling_time``);
        None or no T_s = 0.1 s: not evaluated.
    """
    row = _timing(sampling, "continuous_same_noise", "CS02", "sampling_time")
    statement = "\"Control strategy CS02 deteriorates its performance for sampling time as low as 0.10 s.\""
    definition = f"J_OS(CS02 at T_s = 0.1 s vs continuous) <= -{APPRECIABLE:g} %."
    if row is None or not any(math.isclose(t, 0.1) for t in row):
        return ClaimResult("cs02_deteriorates_at_0.1s", "5.2", statement, definition, "n/a (no T_s = 0.1 s)", None)
    j = row[min(row, key=lambda t: abs(t - 0.1))]
    return ClaimResult("cs02_deteriorates_at_0.1s", "5.2", statement, definition,
                       "CS02 vs continuous: " + ", ".join(f"T_s={t:g} s {v:+.2f} %" for t, v in row.items()),
                       j <= -APPRECIABLE)


def claim_cs01_less_affected(sampling: xr.Dataset | None) -> ClaimResult:
    """§6: sampling affects the feedback strategy CS01 less than the feedback-feedforward strategy CS02
    (at every T_s >= 0.1 s).

    Parameters
    ----------
    sampling : xarray.Dataset or None
        The sampling-time table (:func:`rockstudy.studies.tables.timing_table` over ``sampling_time``);
        None: not evaluated.
    """
    r1 = _timing(sampling, "continuous_same_noise", "CS01", "sampling_time")
    r2 = _timing(sampling, "continuous_same_noise", "CS02", "sampling_time")
    statement = "\"The feedback control strategy is less affected by sampling than the feedback-feedforward one.\""
    definition = "J_OS(CS01 sampled vs continuous) >= J_OS(CS02 sampled vs continuous) at every T_s >= 0.1 s."
    if r1 is None or r2 is None:
        return ClaimResult("cs01_less_affected_by_sampling", "6", statement, definition, "n/a (no sweep)", None)
    common = sorted(t for t in r1 if t in r2 and t >= 0.1 - 1e-9)
    if not common:
        return ClaimResult("cs01_less_affected_by_sampling", "6", statement, definition, "n/a (no T_s >= 0.1 s)",
                           None)
    return ClaimResult("cs01_less_affected_by_sampling", "6", statement, definition,
                       ", ".join(f"T_s={t:g} s: CS01 {r1[t]:+.2f} %, CS02 {r2[t]:+.2f} %" for t in common),
                       all(r1[t] >= r2[t] for t in common))


def claim_cs01_stable_sampled(sampling: xr.Dataset | None) -> ClaimResult:
    """§5.2: CS01 stays more stable than CS02 (J_OS against FS) at every sampling time of the sweep.

    Parameters
    ----------
    sampling : xarray.Dataset or None
        The sampling-time table (:func:`rockstudy.studies.tables.timing_table` over ``sampling_time``);
        None: not evaluated.
    """
    r1 = _timing(sampling, "fs_same_noise", "CS01", "sampling_time")
    r2 = _timing(sampling, "fs_same_noise", "CS02", "sampling_time")
    statement = "\"The feedback strategy CS01 was still the more stable\" over T_s from 2.5 ms to 0.20 s."
    definition = "J_OS(CS01 vs FS) > J_OS(CS02 vs FS) at every sampling time of the sweep."
    if r1 is None or r2 is None:
        return ClaimResult("cs01_more_stable_when_sampled", "5.2", statement, definition, "n/a (no sweep)", None)
    common = sorted(set(r1) & set(r2))
    return ClaimResult("cs01_more_stable_when_sampled", "5.2", statement, definition,
                       ", ".join(f"T_s={t:g} s: CS01 {r1[t]:+.2f} %, CS02 {r2[t]:+.2f} %" for t in common),
                       all(r1[t] > r2[t] for t in common))


def claim_delay(delay: xr.Dataset | None) -> ClaimResult:
    """§5.2 and §6: an actuation delay leaves both strategies' thresholds substantially the same
    (``|J_OS|`` against the same sampling without delay below :data:`APPRECIABLE`).

    Parameters
    ----------
    delay : xarray.Dataset or None
        The delay table (:func:`rockstudy.studies.tables.timing_table` over ``delay``); None: not evaluated.
    """
    statement = ("\"Both strategies perform well with respect to time-delay effects, as the threshold ... remained "
                 "substantially the same\" (delays 2.5 ms and 60 ms, T_s = 100 ms).")
    definition = (f"|J_OS(delayed vs the same sampling without delay)| < {APPRECIABLE:g} % for CS01 and CS02 at every "
                  "delay of the sweep.")
    rows = {s: _timing(delay, "sampled_without_delay_same_noise", s, "delay") for s in ("CS01", "CS02")}
    if any(r is None for r in rows.values()):
        return ClaimResult("delay_harmless", "5.2 / 6", statement, definition, "n/a (no delay sweep)", None)
    evidence = "; ".join(f"{s}: " + ", ".join(f"delay {d * 1000:g} ms {j:+.2f} %" for d, j in r.items())
                         for s, r in rows.items())
    return ClaimResult("delay_harmless", "5.2 / 6", statement, definition, evidence,
                       all(abs(j) < APPRECIABLE for r in rows.values() for j in r.values()))


# --- all together --------------------------------------------------------------------------------
