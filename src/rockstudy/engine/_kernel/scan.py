"""The threshold scan, written once: an upward scan of the amplitude grid, then a bisection between
the last safe and the first overturning grid point down to the resolution.

Every run of a scan takes the stepper of its parameters (Taylor steps between a record's knots unless
``stepper="dopri"``); ``benchmarks/threshold_steppers.py`` measures scans that hand over to
Dormand–Prince runs near the threshold, built from :func:`run_scan`.

:func:`scan_amplitude` / :func:`scan_update` are the scan as a small state machine on a 5-slot
array, so that the compiled :func:`threshold_kernel` and the reference engine's Python loop
(:func:`rockstudy.analysis.spectra.threshold`) drive the very same decisions.
"""
from __future__ import annotations

import math

import numpy as np
from numba import prange

from rockstudy.core._inline import njit
from rockstudy.engine._kernel.engine import driven_bound_data, run_kernel
from rockstudy.engine._kernel.layout import I_ALPHA, I_AMP, I_G, ST_ELIMIT, ST_OVER
from rockstudy.engine.outcome import NO_UPLIFT, OVERTURNED_AFTER_IMPACT, OVERTURNED_WITHOUT_IMPACT, SAFE, UNDETERMINED

# ---- the scan's state: [phase, j, lo, hi, halvings] ---------------------------------------
S_PHASE, S_J, S_LO, S_HI, S_HALVINGS = 0, 1, 2, 3, 4
SCANNING, BISECTING, DONE = 0.0, 1.0, 2.0

SPACING_FLOOR = 4.0
"""The bisection stops once its bracket is at most this many float spacings of its upper end wide,
whatever the resolution asked for: below a float spacing the midpoint is one of the ends. [-]"""
MAX_HALVINGS = 200
"""Cap on the bisection's halvings: a bracket [0, hi] closes at the float spacing of hi within 52
halvings, a bracket up to 2^140 times as wide as its upper end within 200. [-]"""


@njit(cache=True)
def scan_start():
    """A new scan at the first grid point."""
    state = np.zeros(5)
    state[S_PHASE] = SCANNING
    return state


@njit(cache=True)
def scan_amplitude(state, grid):
    """Amplitude ratio to simulate next. [-]"""
    if state[S_PHASE] == SCANNING:
        return grid[int(state[S_J])]
    return 0.5 * (state[S_LO] + state[S_HI])


@njit(cache=True)
def bracket_closed(lo, hi, resolution):
    """True when the bracket [lo, hi] needs no more halving: at most ``resolution`` wide, or at most
    :data:`SPACING_FLOOR` float spacings of ``hi`` (so the bisection ends for any resolution)."""
    width = hi - lo
    return not (width > resolution) or width <= SPACING_FLOOR * np.spacing(abs(hi))


@njit(cache=True)
def scan_update(state, grid, resolution, lower, overturned):
    """Advance the scan with the outcome at :func:`scan_amplitude`; True when it is done.

    ``lower`` is the amplitude ratio below which nothing can uplift (the bracket's floor).
    When done, ``state[S_HI]`` is the threshold (NaN: nothing on the grid overturns) and
    ``state[S_LO]`` the highest amplitude shown safe below it. The bisection ends at ``resolution``,
    at a few float spacings of the bracket (:func:`bracket_closed`), or after :data:`MAX_HALVINGS`
    halvings, whichever comes first.
    """
    if state[S_PHASE] == SCANNING:
        j = int(state[S_J])
        if overturned:
            hi = grid[j]
            lo = grid[j - 1] if j > 0 else lower
            if lo < lower:
                lo = lower
            state[S_LO] = lo
            state[S_HI] = hi
            state[S_PHASE] = DONE if bracket_closed(lo, hi, resolution) else BISECTING
        elif j + 1 >= grid.shape[0]:
            state[S_LO] = grid[grid.shape[0] - 1]
            state[S_HI] = np.nan
            state[S_PHASE] = DONE
        else:
            state[S_J] = j + 1
    else:
        mid = 0.5 * (state[S_LO] + state[S_HI])
        if overturned:
            state[S_HI] = mid
        else:
            state[S_LO] = mid
        state[S_HALVINGS] += 1
        if bracket_closed(state[S_LO], state[S_HI], resolution) or state[S_HALVINGS] >= MAX_HALVINGS:
            state[S_PHASE] = DONE
    return state[S_PHASE] == DONE


@njit(cache=True)
def is_overturned(outcome):
    return outcome == OVERTURNED_WITHOUT_IMPACT or outcome == OVERTURNED_AFTER_IMPACT


@njit(cache=True)
def uplift_floor(vert, unit_peak):
    """Amplitude ratio at or below which the record cannot uplift the block (0: unknown). [-]"""
    if vert.shape[0] == 0 and unit_peak > 0:
        return 1.0 / unit_peak
    return 0.0


_NO = np.zeros(2, dtype=np.bool_)
"""(want_history, want_log) of outcome runs: read from an array, they are typed bool as in the calls
from Python, so the engine is compiled once, not once more for Literal[False]."""


# ---- outcomes and thresholds ----------------------------------------------------------------
@njit(cache=True)
def outcome_kernel(P, rec, vert, amplitude_ratio, unit_peak):
    """:class:`~rockstudy.engine.outcome.Outcome` code of one run at one amplitude ratio."""
    return case_outcome(P, rec, vert, driven_bound_data(P, rec, vert), amplitude_ratio, unit_peak)


@njit(cache=True, inline="always")
def case_outcome(P, rec, vert, B, amplitude_ratio, unit_peak):
    """:func:`outcome_kernel` with the early stop's data ``B`` of the case
    (:func:`rockstudy.engine._kernel.engine.driven_bound_data`), shared by its amplitudes."""
    if vert.shape[0] == 0 and amplitude_ratio * unit_peak <= 1.0:
        return NO_UPLIFT
    Q = P.copy()
    Q[I_AMP] = amplitude_ratio * P[I_G] * math.tan(P[I_ALPHA])
    res = run_kernel(Q, rec, vert, B, _NO[0], _NO[1])
    if res.status == ST_ELIMIT:
        return UNDETERMINED
    if res.status == ST_OVER:
        return OVERTURNED_AFTER_IMPACT if res.n_impacts > 0 else OVERTURNED_WITHOUT_IMPACT
    return SAFE


@njit(cache=True, inline="always")
def run_scan(P, rec, vert, grid, resolution, unit_peak, lower, state, counts):
    """Advance ``state`` with the outcomes of runs of ``P`` until the scan is done; ``counts`` +=
    (simulations, undetermined runs). With ``resolution`` = inf the scan stops at the first grid
    point that overturns (or the last), ``state[S_J]``, without bisecting."""
    done = state[S_PHASE] == DONE
    B = driven_bound_data(P, rec, vert)
    while not done:
        o = case_outcome(P, rec, vert, B, scan_amplitude(state, grid), unit_peak)
        if o != NO_UPLIFT:
            counts[0] += 1
        if o == UNDETERMINED:
            counts[1] += 1
        done = scan_update(state, grid, resolution, lower, is_overturned(o))


@njit(cache=True)
def threshold_kernel(P, rec, vert, grid, resolution, unit_peak):
    """Lowest overturning amplitude ratio on ``grid`` refined to ``resolution``.

    Returns (threshold, lower_safe, n_simulations, n_undetermined); threshold = NaN when nothing
    on the grid overturns. An undetermined run (event cap or step budget) counts as not
    overturned and is counted.
    """
    counts = np.zeros(2, dtype=np.int64)
    state = scan_start()
    run_scan(P, rec, vert, grid, resolution, unit_peak, uplift_floor(vert, unit_peak), state, counts)
    return state[S_HI], state[S_LO], counts[0], counts[1]


@njit(cache=True, inline="always")
def _threshold_case(i, Pm, recs, rec_off, rec_len, vert, grid, resolution, peaks, out, low, nsim, nund):
    rec = recs[rec_off[i]:rec_off[i] + rec_len[i]]
    out[i], low[i], nsim[i], nund[i] = threshold_kernel(Pm[i], rec, vert, grid, resolution, peaks[i])


@njit(cache=True, inline="always")
def _outcome_case(i, Pm, recs, rec_off, rec_len, vert, grid, peaks, out):
    rec = recs[rec_off[i]:rec_off[i] + rec_len[i]]
    B = driven_bound_data(Pm[i], rec, vert)
    for j in range(grid.shape[0]):
        out[i, j] = case_outcome(Pm[i], rec, vert, B, grid[j], peaks[i])


@njit(cache=True, parallel=True)
def threshold_batch(Pm, recs, rec_off, rec_len, vert, grid, resolution, peaks):
    """threshold_kernel over many cases (rows of Pm), in parallel. Returns (threshold, lower_safe,
    n_simulations, n_undetermined), one value per case."""
    n = Pm.shape[0]
    out, low, nsim, nund = np.empty(n), np.empty(n), np.zeros(n, dtype=np.int64), np.zeros(n, dtype=np.int64)
    for i in prange(n):
        _threshold_case(i, Pm, recs, rec_off, rec_len, vert, grid, resolution, peaks, out, low, nsim, nund)
    return out, low, nsim, nund


@njit(cache=True, parallel=True)
def outcome_batch(Pm, recs, rec_off, rec_len, vert, grid, peaks):
    """outcome_kernel on the full (case × amplitude) grid, in parallel over cases."""
    out = np.zeros((Pm.shape[0], grid.shape[0]), dtype=np.int8)
    for i in prange(Pm.shape[0]):
        _outcome_case(i, Pm, recs, rec_off, rec_len, vert, grid, peaks, out)
    return out


@njit(cache=True)
def outcome_serial(Pm, recs, rec_off, rec_len, vert, grid, peaks):
    """:func:`outcome_batch` on one thread: the same results, without numba's parallel machinery (what a
    one-thread job calls for a large map)."""
    out = np.zeros((Pm.shape[0], grid.shape[0]), dtype=np.int8)
    for i in range(Pm.shape[0]):
        _outcome_case(i, Pm, recs, rec_off, rec_len, vert, grid, peaks, out)
    return out
