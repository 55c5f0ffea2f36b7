"""The driving loop of the fast engine (paper §3), in small compiled parts around one state record.

A run is a parameter vector ``P`` (:mod:`.layout`, ``I_*``), the run's constants ``C`` derived from it
once (:func:`setup`, ``C_*``) and the state record ``S`` (:func:`initial_state`, ``R_*``: time,
θ, θ̇, side, mode, device state, element flags, counters, the step size). Between known-time events
(the end of the excitation, record knots, controller samples and actuation instants,
:func:`next_known_time`) the block is on the ground or held (:func:`ground_phase`) or rocks under
Taylor steps between the knots of a record or Dormand–Prince steps (:func:`integrate`); each
accepted step is searched for state events, the earliest is located
and its map applied (:func:`state_event`); the known-time events are applied by
:func:`known_time_events`, the CS01 apex decision by :func:`apex`. :func:`drive` runs them in turn
and writes the history and the event logs as far as they have room (their fill levels in ``N``,
``N_*``); :func:`simulate_kernel` grows them and calls it again. Every part takes the records
(``S``, ``C``, ``P``) rather than their values one by one; a run is capped at ``MAX_EVENTS`` located
events and ``MAX_STEPS`` steps and passes.

The equation of motion, impacts, uplift and the REST/HOLD exits read the driving Ẍg
(``ground_acceleration``); the control law's decisions (CS02's sign of Ẍg, its Ẍg = 0 switch,
sampled decisions) read Ẍg as the controller senses it (``sensed_acceleration``, equal to the
driving Ẍg without a sensor; :mod:`rockstudy.model.sensor`).

The model and every reading of the paper are in ``docs/model.md``.
"""
from __future__ import annotations

import math

import numpy as np

from rockstudy.core._inline import NO_REFCOUNT, guarded_pow, inline_into, njit
from rockstudy.core.constants import (
    FIRST_STEP,
    IMPACT_TOLERANCE,
    MAX_EVENTS,
    MAX_STEPS,
    NEGLIGIBLE_STEP,
    ROTATION_TOLERANCE,
    TIME_TOLERANCE,
)
from rockstudy.engine._kernel import dopri, maps, taylor
from rockstudy.engine._kernel.events import (
    event_poly,
    locate_poly,
    locate_sensed_poly,
    scan_exit,
)
from rockstudy.engine._kernel.ground import ground_acceleration, sensed_acceleration, vertical_acceleration
from rockstudy.engine._kernel.layout import (
    B_LEVEL,
    B_PUMP,
    B_RATCHET,
    B_SCALE,
    B_TAIL,
    B_UPLIFT,
    C_BOUND,
    C_BOUND_SWITCHING,
    C_CD,
    C_DRIVEN,
    C_EXC_END,
    C_FRACTURE,
    C_HISTORY,
    C_KMAX,
    C_KMIN,
    C_LOG,
    C_QUIET_KNOTS,
    C_SAMPLED,
    C_SWITCHING,
    C_T_STOP,
    C_TAYLOR,
    C_V_END,
    I_ALPHA,
    I_AMP,
    I_ATOL,
    I_BOUND,
    I_CD,
    I_COSA,
    I_DELAY,
    I_DUR,
    I_E,
    I_FREE,
    I_G,
    I_HMAX,
    I_KIND,
    I_KMAX,
    I_KMIN,
    I_P,
    I_RDT,
    I_RTOL,
    I_SENSE,
    I_SINA,
    I_SOFF,
    I_STRAT,
    I_TAYLOR,
    I_TDU,
    I_TH0,
    I_THD0,
    I_TKU,
    I_TOVER,
    I_TS,
    I_VDT,
    I_VREST,
    LEFT,
    MODE_HOLD,
    MODE_REST,
    MODE_ROCK,
    N_HISTORY,
    N_IMPACTS,
    N_RESTS,
    N_UPLIFTS,
    NCONST,
    NFILL,
    NSTATE,
    R_APEX,
    R_CHECK,
    R_DAMPER,
    R_F0,
    R_F0_OK,
    R_FRAC,
    R_H,
    R_H_ON,
    R_HINT,
    R_K_SAMPLE,
    R_KAP_ON,
    R_MAX_ABS,
    R_MODE,
    R_N_EVENTS,
    R_N_IMPACTS,
    R_N_STEPS,
    R_Q_COUNT,
    R_Q_HEAD,
    R_RESUME,
    R_SIDE,
    R_SPRING,
    R_T,
    R_T_NEXT,
    R_T_OVER,
    R_TH,
    R_THD,
    R_X_HINT,
    RIGHT,
    ST_BOUND,
    ST_ELIMIT,
    ST_OVER,
    ST_REST,
    ST_TLIM,
    KernelResult,
)
from rockstudy.engine._kernel.maps import sign
from rockstudy.model.control import CS01, CS02, FS, PASSIVE, stiffness_on
from rockstudy.model.excitation import MODULATED, RECORD

GROWTH_CAP_ERROR = 5.8e-6
"""Below this scaled error a step's successor grows by the cap, 10x (0.9·err^-0.2 > 10.03)."""
GROWTH_MARGIN = 1e-9
"""Relative margin of :func:`_grows_past`, far above the rounding of the power and the products."""

# what a part of the loop reports to the driver (which logs it)
NOTHING, UPLIFTED, LEFT_HOLD, HELD = 0, 1, 2, 3
STEPPED, EVENT, OVERTURNED, NEED_ROOM = 0, 1, 2, 3
GROW = -1  # drive: an array is full; grow it and call again
IMPACT, IMPACT_UPLIFT, IMPACT_REST = 4, 5, 6


# ---- growable logs: written by the loop, grown by simulate_kernel ---------------------------
HISTORY_RESERVE = 3
"""Rows of the history array the driver keeps free for its own rows (``integrate`` stops short of them)."""
LOG_RESERVE = 2
"""Free slots each event log keeps at the top of the driver's loop (one pass adds at most two)."""


@njit(cache=True)
def _hist_full(H, n):
    """True when the history array has no more room than the driver's reserve."""
    return n + HISTORY_RESERVE >= H.shape[0]


@njit(cache=True)
def _log_full(arr, n):
    return n + LOG_RESERVE > arr.shape[0]


@njit(cache=True)
def _grow_log(arr, n):
    """An event log twice as long (at least 16 slots) holding the first ``n`` values of ``arr``."""
    new = np.empty(max(16, 2 * arr.shape[0]))
    for i in range(n):  # element by element: a slice assignment compiles numba's shape-mismatch message
        new[i] = arr[i]
    return new


@njit(cache=True)
def _write_log(arr, n, v):
    arr[n] = v
    return n + 1


@njit(cache=True)
def _grow_hist(H, n):
    """A history array twice as long (at least 256 rows) holding the first ``n`` rows of ``H``."""
    new = np.empty((max(256, 2 * H.shape[0]), 5))
    for i in range(n):  # element by element, as _grow_log
        for j in range(5):
            new[i, j] = H[i, j]
    return new


@njit(cache=True)
def _write_hist(H, n, t, th, thd, kap, xg):
    """Row ``n`` of the history (the caller has made room)."""
    H[n, 0] = t
    H[n, 1] = th
    H[n, 2] = thd
    H[n, 3] = kap
    H[n, 4] = xg
    return n + 1


@njit(cache=True)
def _next_knot(t, dt):
    """The sampling instant after t of a record sampled every dt. [s]"""
    return (math.floor(t / dt + 1e-7) + 1.0) * dt


# ---- small readers of the state ---------------------------------------------------------
@njit(cache=True)
def _flag(x):
    return 1.0 if x else 0.0


@njit(cache=True)
def _working(S):
    """Index of the working-side corner elements (LEFT for θ > 0, RIGHT for θ < 0)."""
    return LEFT if S[R_SIDE] > 0 else RIGHT


@njit(cache=True)
def _device(S, C):
    """κ of the device state in use (before the working spring's fracture function). [-]"""
    return C[C_KMAX] if S[R_KAP_ON] != 0.0 else C[C_KMIN]


@njit(cache=True, inline="always")
def _xg(S, P, rec):
    """Ẍg at the state's time while the horizontal excitation lasts, else 0. [m/s^2]"""
    return ground_acceleration(S[R_T], P, rec) if S[R_H_ON] != 0.0 else 0.0


@njit(cache=True, **NO_REFCOUNT)
def _ground_at(t, P, rec):
    """:func:`ground_acceleration` as a call, where it is seldom read (a history row, a segment's start). [m/s^2]"""
    return ground_acceleration(t, P, rec)


@njit(cache=True)
def _sensed(S, P, rec):
    """Ẍg as the controller senses it at the state's time while the excitation lasts, else 0. [m/s^2]"""
    return sensed_acceleration(S[R_T], P, rec) if S[R_H_ON] != 0.0 else 0.0


@njit(cache=True)
def _turn(S, turn):
    """Apply a CS01 apex decision that leaves θ̇ = 0: K_max and outward, or K_min and back."""
    S[R_KAP_ON] = _flag(turn == maps.TURN_OUT)
    S[R_HINT] = S[R_SIDE] if S[R_KAP_ON] != 0.0 else -S[R_SIDE]


# ---- setup --------------------------------------------------------------------------------
@njit(cache=True)
def takes_taylor_steps(P, nvert):
    """True when runs of ``P`` take Taylor steps between record knots: ``P[I_TAYLOR]``, a record,
    no vertical record (``nvert`` samples of it)."""
    return P[I_TAYLOR] != 0.0 and int(P[I_KIND]) == RECORD and nvert == 0


@njit(cache=True)
def setup(P, vert, want_history, want_log):
    """The run's constants ``C`` (``C_*`` slots): the device the strategy uses, the time limits and
    the flags that select the events, the early stop, the stepper and what the run records."""
    C = np.zeros(NCONST)
    strategy = int(P[I_STRAT])
    kmax = P[I_KMAX]
    kmin = P[I_KMIN]
    cdamp = P[I_CD]
    if strategy == FS:
        kmax = 0.0
        kmin = 0.0
        cdamp = 0.0
    if strategy == PASSIVE:
        kmin = kmax
    sampled = P[I_TS] > 0.0
    nvert = vert.shape[0]
    v_end = (nvert - 1) * P[I_VDT] if nvert > 0 else 0.0
    exc_end = max(P[I_DUR], v_end)
    C[C_KMAX] = kmax
    C[C_KMIN] = kmin
    C[C_CD] = cdamp
    C[C_V_END] = v_end
    C[C_EXC_END] = exc_end
    C[C_T_STOP] = exc_end + P[I_FREE]
    C[C_SAMPLED] = _flag(sampled)
    C[C_SWITCHING] = _flag((not sampled) and (strategy == CS01 or strategy == CS02) and kmax != kmin)
    C[C_FRACTURE] = _flag(strategy != FS and (kmax > 0.0 or cdamp > 0.0))
    # end the run once it provably cannot overturn any more (outcome runs only)
    C[C_BOUND] = _flag(P[I_BOUND] != 0.0 and not want_history and not want_log)
    # with sampled control a stale K_max can give energy back: a weaker bound over half-cycles
    C[C_BOUND_SWITCHING] = _flag(sampled and kmax != kmin)
    C[C_QUIET_KNOTS] = _flag(int(P[I_KIND]) == RECORD and nvert == 0 and not want_history)
    # Taylor steps between record knots: Ẍg linear on every step, no vertical motion (docs/model.md)
    C[C_TAYLOR] = _flag(takes_taylor_steps(P, nvert))
    C[C_HISTORY] = _flag(want_history)
    C[C_LOG] = _flag(want_log)
    # the early stop during the excitation (no vertical record: its Ÿg would change the potential)
    if C[C_BOUND] != 0.0 and nvert == 0:
        pumps = kmax != kmin and (sampled or strategy == CS02)
        C[C_DRIVEN] = maps.DRIVEN_SWITCHING if pumps else maps.DRIVEN_STEADY
    return C


_NO = np.zeros(2, dtype=np.bool_)
"""(want_history, want_log) of :func:`driven_bound_data`'s call of :func:`setup`: read from an array, they
are typed bool as in :func:`run_kernel`'s call, so ``setup`` is compiled once, not once more for
Literal[bool](False)."""


@njit(cache=True)
def driven_bound_data(P, rec, vert):
    """The data of the early stop during the excitation (``B_*`` slots), the same for every amplitude of
    a case: the level its bound must stay below, the impulse per unit of ∫|Ẍg| dt and, for a record, the
    integral of |record| from each knot to the end of the excitation (linear pieces bounded by the mean
    of their ends' magnitudes) and the largest |record| from each knot on. Two slots (and no stop) when the
    run cannot stop early."""
    C = setup(P, vert, _NO[0], _NO[1])
    kind = int(C[C_DRIVEN])
    n = 0
    if kind != maps.DRIVEN_NONE and int(P[I_KIND]) == RECORD:
        n = int(P[I_SOFF]) if P[I_SENSE] != 0.0 else rec.shape[0]
    B = np.zeros(B_TAIL + 2 * n)
    if kind == maps.DRIVEN_NONE:
        return B
    alpha = P[I_ALPHA]
    if kind == maps.DRIVEN_STEADY:
        B[B_LEVEL] = (1.0 - math.cos(alpha)) * (1.0 - maps.DRIVEN_MARGIN)
    else:
        B[B_LEVEL] = maps.switching_level(alpha, P[I_E], C[C_KMAX], C[C_KMIN], C[C_SAMPLED] != 0.0)
    B[B_SCALE] = P[I_P] / (math.sqrt(2.0) * P[I_G])
    if kind == maps.DRIVEN_SWITCHING:
        B[B_PUMP] = P[I_P] / math.sqrt(2.0) * C[C_KMAX] * math.sin(maps.peak_rotation(B[B_LEVEL], alpha))
        maps.ratchet_levels(alpha, P[I_E], C[C_KMAX], B, B_RATCHET)
    B[B_UPLIFT] = P[I_G] * math.tan(alpha)
    if n > 0:
        dt = P[I_RDT]
        dur = P[I_DUR]
        last = (n - 1) * dt
        acc = (dur - last) * abs(rec[n - 1]) if dur > last else 0.0
        B[B_TAIL + n - 1] = acc
        peak = abs(rec[n - 1])
        B[B_TAIL + 2 * n - 1] = peak
        for k in range(n - 2, -1, -1):
            if k * dt < dur:
                acc += 0.5 * dt * (abs(rec[k]) + abs(rec[k + 1]))
            B[B_TAIL + k] = acc
            peak = max(peak, abs(rec[k]))
            B[B_TAIL + n + k] = peak
    return B


@njit(cache=True)
def initial_state(P, C, rec):
    """The state record ``S`` (``R_*`` slots) at t = 0."""
    S = np.zeros(NSTATE)
    th = P[I_TH0]
    thd = P[I_THD0]
    S[R_TH] = th
    S[R_THD] = thd
    S[R_H_ON] = 1.0
    S[R_SPRING:R_SPRING + 2] = 1.0
    S[R_DAMPER:R_DAMPER + 2] = 1.0
    S[R_FRAC:R_FRAC + 4] = np.nan
    S[R_KAP_ON] = 1.0
    if th != 0.0:
        S[R_SIDE] = sign(th)
    elif thd != 0.0:
        S[R_SIDE] = sign(thd)
    else:
        S[R_SIDE] = 1.0
    S[R_MODE] = MODE_ROCK if (th != 0.0 or thd != 0.0) else MODE_REST
    S[R_T_OVER] = np.nan
    S[R_MAX_ABS] = abs(th)
    strategy = int(P[I_STRAT])
    if C[C_SAMPLED] == 0.0:
        S[R_KAP_ON] = _flag(stiffness_on(strategy, th, thd, sensed_acceleration(0.0, P, rec)))
        S[R_HINT] = sign(thd)
    S[R_APEX] = _flag(C[C_SWITCHING] != 0.0 and S[R_MODE] == MODE_ROCK and thd == 0.0 and th != 0.0
                      and strategy == CS01)
    S[R_H] = min(FIRST_STEP, P[I_HMAX])
    S[R_CHECK] = 1.0
    return S


# ---- the parts of the loop ------------------------------------------------------------------
@njit(cache=True)
def next_known_time(S, C, P, vert, queue_times):
    """The next known-time event after the state's time: the end of the excitation, a record knot,
    a controller sample or an actuation instant, or the end of the run. [s]"""
    t = S[R_T]
    t_next = C[C_T_STOP]
    h_on = S[R_H_ON] != 0.0
    h_end = P[I_DUR]
    if h_on and h_end < t_next:
        t_next = max(h_end, t)
    if h_on and int(P[I_KIND]) == RECORD:  # Ẍg is linear between knots: steps end at each
        tk = _next_knot(t, P[I_RDT])
        if tk < t_next:
            t_next = tk
    if vert.shape[0] > 0 and t < C[C_V_END]:
        tk = _next_knot(t, P[I_VDT])
        if tk < t_next:
            t_next = tk
    if C[C_SAMPLED] != 0.0:
        ts_ = S[R_K_SAMPLE] * P[I_TS]
        if ts_ < t_next:
            t_next = ts_
        if S[R_Q_COUNT] > 0 and queue_times[int(S[R_Q_HEAD])] < t_next:
            t_next = queue_times[int(S[R_Q_HEAD])]
    if t_next < t:
        t_next = t
    return t_next


@njit(cache=True, **NO_REFCOUNT)
def ground_phase(S, C, P, rec, vert, t_next):
    """REST or HOLD up to ``t_next``: find the exit (uplift; leaving the CS01 sliding surface) and
    apply it. Returns NOTHING (still there at ``t_next``), UPLIFTED or LEFT_HOLD."""
    t = S[R_T]
    mode = int(S[R_MODE])
    side = S[R_SIDE]
    sidx = _working(S)
    h_on = S[R_H_ON] != 0.0
    kap_max_eff = C[C_KMAX] * S[R_SPRING + sidx]
    kap_min_eff = C[C_KMIN] * S[R_SPRING + sidx]
    if t_next > t:
        t_exit = scan_exit(mode, t, t_next, S[R_TH], side, kap_max_eff, kap_min_eff, h_on, P, rec, vert)
    else:
        t_exit = -1.0
    if t_exit < 0.0:
        S[R_T] = t_next  # nothing happens before the next known-time event
        return NOTHING
    S[R_T] = t_exit
    S[R_N_EVENTS] += 1
    xg = _xg(S, P, rec)
    if mode == MODE_REST:  # uplift
        side = maps.uplift_side(xg)
        S[R_SIDE] = side
        S[R_TH] = 0.0
        S[R_THD] = 0.0
        S[R_MODE] = MODE_ROCK
        if C[C_SAMPLED] == 0.0:
            S[R_KAP_ON] = _flag(stiffness_on(int(P[I_STRAT]), side, 0.0, _sensed(S, P, rec)))
        S[R_HINT] = side
        return UPLIFTED
    # leaves the sliding surface, outward or back (never HOLD again here)
    yg = vertical_acceleration(t_exit, P, vert)
    _turn(S, maps.apex_decision(S[R_TH], side, kap_max_eff, kap_min_eff, xg, yg, P))
    S[R_MODE] = MODE_ROCK
    S[R_THD] = 0.0
    return LEFT_HOLD


@njit(cache=True, **NO_REFCOUNT)
def pass_quiet_knots(S, C, P, rec, vert, B, queue_times, queue_values, t_next):
    """REST under a record without vertical motion: pass the known-time events before the end of the
    excitation at which the block is still at rest in one loop. Each gets what the driver's loop would
    give it — the same uplift test there (:func:`ground_phase`), the same known-time events (at a record
    knot none: it changes nothing, only a pending apex invalidates the stored derivative; with sampled
    control the controller's samples and decisions, :func:`known_time_events`, and the driver's count of
    passes and its early stop at rest, :func:`below_driven_bound`) and the same next known time —
    without the rest of the loop. Returns the known-time event from which :func:`ground_phase` goes on
    (the state's own time when the driver is to end the run there). [s]"""
    # events.exit_value's REST test, (g + Ÿg)·tanα with Ÿg = 0 (no vertical record here), its tan
    # taken once and the ground reading inlined: the same bits without a call per knot
    uplift = P[I_G] * math.tan(P[I_ALPHA])
    sampled = C[C_SAMPLED] != 0.0
    while t_next < P[I_DUR] and t_next > S[R_T]:
        if abs(ground_acceleration(t_next, P, rec)) - uplift > 0.0:
            break  # uplift inside (t, t_next]: ground_phase locates it
        S[R_T] = t_next
        if S[R_APEX] != 0.0:
            S[R_F0_OK] = 0.0
        if sampled:  # the driver's pass ends with these events; its next pass starts with its checks
            known_time_events(S, C, P, rec, queue_times, queue_values)
            if S[R_N_STEPS] > MAX_STEPS:
                return S[R_T]
            S[R_N_STEPS] += 1.0
            if C[C_DRIVEN] != 0.0 and below_driven_bound(S, C, P, B):
                return S[R_T]
        t_next = next_known_time(S, C, P, vert, queue_times)
    return t_next


@njit(cache=True, inline=inline_into("drive", "integrate", "pass_quiet_knots"), **NO_REFCOUNT)
def known_time_events(S, C, P, rec, queue_times, queue_values):
    """Apply what happens at a known-time event: the end of the excitation, controller samples due
    (decision k taken at k·T_s acts from k·T_s + Δτ), decisions that act now. A record knot
    changes nothing."""
    t = S[R_T]
    strategy = int(P[I_STRAT])
    kap_before = S[R_KAP_ON]
    h_before = S[R_H_ON]
    if S[R_H_ON] != 0.0 and t >= P[I_DUR]:  # the excitation ends
        S[R_H_ON] = 0.0
        if C[C_SWITCHING] != 0.0:
            S[R_KAP_ON] = _flag(stiffness_on(strategy, S[R_TH], S[R_THD], 0.0))
            S[R_HINT] = sign(S[R_THD])
            if S[R_THD] == 0.0 and S[R_TH] != 0.0 and S[R_MODE] == MODE_ROCK:
                S[R_APEX] = 1.0
    if C[C_SAMPLED] != 0.0:
        Ts = P[I_TS]
        head = int(S[R_Q_HEAD])
        count = int(S[R_Q_COUNT])
        while S[R_K_SAMPLE] * Ts <= t + TIME_TOLERANCE:  # controller samples due
            on = stiffness_on(strategy, S[R_TH], S[R_THD], _sensed(S, P, rec))
            count = maps.queue_push(queue_times, queue_values, head, count, S[R_K_SAMPLE] * Ts + P[I_DELAY], on)
            S[R_K_SAMPLE] += 1
        while count > 0 and queue_times[head] <= t + TIME_TOLERANCE:  # decisions that act now
            S[R_KAP_ON] = _flag(queue_values[head])
            head = (head + 1) % queue_times.shape[0]
            count -= 1
        S[R_Q_HEAD] = head
        S[R_Q_COUNT] = count
    if S[R_KAP_ON] != kap_before or S[R_H_ON] != h_before or S[R_APEX] != 0.0:
        S[R_F0_OK] = 0.0


@njit(cache=True, **NO_REFCOUNT)
def below_overturning_energy(S, C, P):
    """True when the block, free of excitation, provably cannot overturn any more (docs/model.md)."""
    if C[C_BOUND_SWITCHING] != 0.0:
        return maps.cannot_overturn_switching(S[R_TH], S[R_THD], S[R_SIDE], P[I_P], P[I_ALPHA], P[I_E], C[C_KMAX])
    return maps.cannot_overturn(S[R_TH], S[R_THD], P[I_P], P[I_ALPHA], C[C_KMIN] * S[R_SPRING + _working(S)])


@njit(cache=True)
def _knot_before(t, P, B):
    """Index of the record knot one before the one at or before t, within the record of ``B``."""
    return min(max(int(t / P[I_RDT]) - 1, 0), (B.shape[0] - B_TAIL) // 2 - 1)


UPLIFT_MARGIN = 1e-9
"""Relative margin of the test that a resting block can no longer uplift: over the rounding of the
interpolated record and of the products. [-]"""


@njit(cache=True, inline="always")
def cannot_uplift_any_more(t, P, B):
    """True when, under a record, |Ẍg| stays at or below g·tanα from t to the end of the excitation, so a
    block at rest there stays at rest (no vertical record here; Ẍg between knots lies between theirs)."""
    if int(P[I_KIND]) != RECORD:
        return False
    n = (B.shape[0] - B_TAIL) // 2
    peak = B[B_TAIL + n + _knot_before(t, P, B)]
    return abs(P[I_AMP]) * peak * (1.0 + UPLIFT_MARGIN) <= B[B_UPLIFT] * (1.0 - UPLIFT_MARGIN)


@njit(cache=True, inline="always")
def remaining_input(t, P, B):
    """An upper bound of ∫ from t to the end of the excitation of |Ẍg|/a_p. [s]"""
    dur = P[I_DUR]
    if t >= dur:
        return 0.0
    kind = int(P[I_KIND])
    if kind == RECORD:  # from the knot before t (one earlier, against the rounding of t/dt)
        return B[B_TAIL + _knot_before(t, P, B)]
    if kind == MODULATED:  # |Eq. 23| <= its envelope 90 s²(1 − s)⁶, integrated in closed form
        y = min(max(1.0 - t / dur, 0.0), 1.0)
        y7 = y ** 7
        return dur * 90.0 * y7 * (1.0 / 7.0 - 0.25 * y + y * y / 9.0)
    return dur - t  # one-sine pulse and rectangular pulse: |Ẍg| <= a_p


@njit(cache=True, inline=inline_into("drive", "pass_quiet_knots"))
def below_driven_bound(S, C, P, B):
    """True when the block, still under excitation, provably cannot overturn whatever the rest of
    the excitation does within its impulse (docs/engine.md, "Early stops"). The impulse bound is tested
    at the start and after each state event (``R_CHECK``), not at every known-time event in between (a
    sampled run passes the driver at every controller sample); a resting block's uplift at every pass."""
    t = S[R_T]
    if not B[B_LEVEL] > 0.0:
        return False
    if S[R_MODE] == MODE_REST and cannot_uplift_any_more(t, P, B):
        return True
    if S[R_CHECK] == 0.0:  # nothing new since the last test: at the next state event
        return False
    S[R_CHECK] = 0.0
    impulse = B[B_SCALE] * abs(P[I_AMP]) * remaining_input(t, P, B)
    return maps.cannot_overturn_driven(S[R_TH], S[R_THD], P[I_P], P[I_ALPHA], impulse, int(C[C_DRIVEN]),
                                       C[C_KMIN] * S[R_SPRING + _working(S)], B[B_LEVEL],
                                       B[B_PUMP] * (C[C_EXC_END] - t), C[C_KMAX], B, B_RATCHET)


@njit(cache=True, inline=inline_into("drive"))
def apex(S, C, P, rec, vert):
    """The CS01 switch at θ̇ = 0 (docs/model.md, "CS01 sliding"): turn out with K_max, back with
    K_min, or hold. Returns HELD or NOTHING."""
    S[R_APEX] = 0.0
    side = S[R_SIDE]
    sidx = _working(S)
    yg = vertical_acceleration(S[R_T], P, vert)
    turn = maps.apex_decision(S[R_TH], side, C[C_KMAX] * S[R_SPRING + sidx], C[C_KMIN] * S[R_SPRING + sidx],
                              _xg(S, P, rec), yg, P)
    S[R_THD] = 0.0
    if turn == maps.HOLD:
        S[R_MODE] = MODE_HOLD
        return HELD
    _turn(S, turn)
    return NOTHING


@njit(cache=True)
def _events_used(S, C, P):
    """(CS01-type switch at θ̇ = 0, CS02 switch at Ẍg = 0) located in this state."""
    switching = C[C_SWITCHING] != 0.0
    strategy = int(P[I_STRAT])
    h_on = S[R_H_ON] != 0.0
    return switching and (strategy == CS01 or not h_on), switching and strategy == CS02 and h_on


@njit(cache=True)
def _grown_step(hh, err):
    """The trial step after an accepted step of size ``hh`` with scaled error ``err`` <= 1:
    0.9·err^(-1/5) times ``hh``, at most 10 times. [s]"""
    # growth capped at 10x: 0.9·err^-0.2 >= 10 for err <= 5.9e-6, so the power is only taken above
    return hh * min(10.0, 0.9 * guarded_pow(err, -0.2)) if err > GROWTH_CAP_ERROR else hh * 10.0


@njit(cache=True)
def _grows_past(hh, err, d):
    """True only when ``_grown_step(hh, err) >= d`` for certain, decided without the power.

    Most steps end on a record knot with a far smaller error than the tolerance allows, so the next
    step is cut at the next knot whatever the grown step is: the power is then not needed.
    0.9·err^-0.2 >= d/hh is err <= (0.9·hh/d)^5; ``GROWTH_MARGIN`` covers the rounding of both
    sides, so a case near the boundary computes the power.
    """
    if err <= GROWTH_CAP_ERROR:
        return hh * 10.0 >= d
    x = 0.9 * hh / d
    return hh * 10.0 >= d * (1.0 + GROWTH_MARGIN) and err <= x * x * x * x * x * (1.0 - GROWTH_MARGIN)


@njit(cache=True, inline="always")
def _segment_start(t, th, thd, f0, side, use_xg_event, x_hint, hint, h, P, rec):
    """What a run of steps from t starts with: the sign of the sensed Ẍg (CS02 switch event), the
    sign θ̇ will have (CS01 switch event), and a first step kept inside the excursion after θ = 0.
    Returns (x_hint, hint, h)."""
    if use_xg_event:
        xs = sensed_acceleration(t, P, rec)
        if xs == 0.0:
            xs = sensed_acceleration(t + 1e-9, P, rec)
        x_hint = sign(xs)
    if thd != 0.0:
        hint = sign(thd)
    # after an impact or uplift (θ = 0) keep the first step inside the excursion
    if th == 0.0 and side * f0 < 0.0 and side * thd > 0.0:
        h = min(h, 0.5 * abs(thd / f0))
    return x_hint, hint, h


@njit(cache=True, inline="always")
def _locate_on(hi, Q, a_th, a_thd, c):
    """The first zero in (0, hi] of g = a_th·θ + a_thd·θ̇ + c on the step's polynomial in ``Q``: degree 6
    after a Taylor step, the quartic after a Dormand–Prince step (whose columns 5 and 6 are 0, so g5 = g6
    = 0 and the Horner values are the quartic's own), by one compiled locator for both."""
    return locate_poly(hi, *event_poly(Q, a_th, a_thd, c))


@njit(cache=True, **NO_REFCOUNT)
def _locate_cold(hi, Q, a_th, a_thd, c):
    """:func:`_locate_on` as a call, for the event searches that seldom locate (a rotation threshold, the
    CS01 switch away from an apex): one compiled copy instead of one inlined at each."""
    return _locate_on(hi, Q, a_th, a_thd, c)


@njit(cache=True)
def _locate_sensed_on(hi, Q, x_hint, t, hh, P, rec):
    """:func:`_locate_on` for the CS02 switch (θ terms none, the sensed Ẍg's sign ``x_hint``)."""
    return locate_sensed_poly(hi, *event_poly(Q, 0.0, 0.0, 0.0), x_hint, t, hh, P, rec)


@njit(cache=True, inline="always")
def _coefficients_once(have_q, hh, y0, y1, K, Q):
    """Write the step's dense-output coefficients to ``Q`` unless this step already has; True."""
    if not have_q:
        dopri.dense_coefficients(hh, y0, y1, K, Q)
    return True


@njit(cache=True, inline="always")
def segment_events(S, C, P):
    """What the event search looks for while the steps from the state last (a fracture, a switch, the
    end of the excitation end them first): (side, CS01 switch, CS02 switch, overturning rotation θ_over,
    θ_K,u and θ_D,u of the working side's intact elements (inf: none that can break), Taylor steps).
    Read once from the records ``S``, ``C``, ``P`` by :func:`integrate` for all its steps."""
    sidx = _working(S)
    use_thd_event, use_xg_event = _events_used(S, C, P)
    fracture = C[C_FRACTURE] != 0.0
    th_ku = P[I_TKU] if fracture and S[R_SPRING + sidx] > 0.0 else math.inf
    th_du = P[I_TDU] if fracture and S[R_DAMPER + sidx] > 0.0 else math.inf
    return S[R_SIDE], use_thd_event, use_xg_event, P[I_TOVER], th_ku, th_du, C[C_TAYLOR] != 0.0 and S[R_H_ON] != 0.0


@njit(cache=True, inline="always")
def search_events(seg, P, rec, K, Q, t, hh, y0, y1, n0, n1, hint, x_hint, max_abs):
    """The event search of one accepted step from (θ, θ̇) = (y0, y1) at t to (n0, n1) at t + hh (its
    stages in ``K``), for the events of the segment ``seg`` (:func:`segment_events`): the earliest state
    event on (t, t + hh] — an impact (side·θ reaches 0), the overturning rotation, a working element's
    ultimate rotation, the CS01 switch (θ̇ = 0, sign ``hint`` before it), the CS02 switch (sensed
    Ẍg = 0, sign ``x_hint`` before it) — located on the continuous extension, whose coefficients are
    written to ``Q`` when an event is to be located (a Taylor step has written them already).

    Returns (best, negligible, max_abs): ``best`` the event's fraction of the step (> 1: none;
    < 0: θ left 0 and came back within the step, which must be retried with a smaller one),
    ``negligible`` True for such an excursion within a step <= NEGLIGIBLE_STEP (it ends at the
    step's end), ``max_abs`` the largest |θ| updated by an apex inside the step.
    """
    side, use_thd_event, use_xg_event, th_over, th_ku, th_du, have_q = seg  # a Taylor step has written Q
    best = 2.0
    negligible = False
    # impact: side·θ crosses to <= 0 (located below, after the apex)
    impact = False
    if side * n0 <= 0.0:
        if side * y0 > 0.0:
            impact = True
        elif hh > NEGLIGIBLE_STEP:
            return -1.0, False, max_abs
        else:
            negligible = True  # an excursion shorter than NEGLIGIBLE_STEP: it ends at t + hh
            best = 1.0
    # an apex inside the step: the largest rotation may lie between the step ends, and a
    # rotation threshold may be crossed and re-crossed within the step (grazing)
    apex = not negligible and side * y1 > 0.0 and side * n1 <= 0.0
    peak = side * n0
    sig_peak = 1.0
    sa_ = -1.0
    if apex:
        have_q = _coefficients_once(have_q, hh, y0, y1, K, Q)
        sa_ = _locate_on(1.0, Q, 0.0, side, 0.0)
        if sa_ >= 0.0:
            a, b = dopri.dense_at(sa_, Q)
            if side * a > peak:
                peak = side * a
                sig_peak = sa_
            if abs(a) > max_abs:
                max_abs = abs(a)
    # the CS01 switch at this apex (θ̇ = 0 while moving away from the ground) is an event before any
    # impact in the step, which θ reaches only after its apex: then the impact need not be located
    apex_switch = use_thd_event and hint == side and apex
    if impact and not (apex_switch and sa_ >= 0.0 and sig_peak == sa_):
        have_q = _coefficients_once(have_q, hh, y0, y1, K, Q)
        best = _locate_on(1.0, Q, side, 0.0, 0.0)
    if not negligible and peak - th_over >= 0.0 and side * y0 - th_over < 0.0:
        have_q = _coefficients_once(have_q, hh, y0, y1, K, Q)
        s = _locate_cold(min(best, sig_peak), Q, -side, 0.0, th_over)
        if s >= 0.0:
            best = s
    for k in range(2):  # the working side's intact elements (th_ku, th_du = inf: none that can break)
        thu = th_ku if k == 0 else th_du
        if not negligible and side * y0 - thu < 0.0 and peak - thu >= 0.0:
            have_q = _coefficients_once(have_q, hh, y0, y1, K, Q)
            s = _locate_cold(min(best, sig_peak), Q, -side, 0.0, thu)
            if s >= 0.0:
                best = s
    if not negligible and use_thd_event and hint != 0.0 and hint * n1 <= 0.0:
        if apex_switch:
            # the apex located above is the first zero of the same function on (0, 1], so also the
            # one on (0, min(best, 1)] when it lies there; beyond it, there is none there
            s = sa_ if sa_ <= min(best, 1.0) else -1.0
        else:
            have_q = _coefficients_once(have_q, hh, y0, y1, K, Q)
            s = _locate_cold(min(best, 1.0), Q, 0.0, hint, 0.0)
        if s >= 0.0:
            best = s
    if not negligible and use_xg_event and x_hint != 0.0:
        if x_hint * sensed_acceleration(t + hh, P, rec) <= 0.0:
            have_q = _coefficients_once(have_q, hh, y0, y1, K, Q)
            s = _locate_sensed_on(min(best, 1.0), Q, x_hint, t, hh, P, rec)
            if s >= 0.0:
                best = s
    return best, negligible, max_abs


@njit(cache=True)
def _event_point(best, negligible, t, hh, n0, n1, Q):
    """(t, θ, θ̇) at the located event, fraction ``best`` of the step: the step's end itself when
    best = 1, back on the ground (θ = θ̇ = 0) after a negligible excursion."""
    if negligible:
        return t + hh, 0.0, 0.0
    if best == 1.0:
        return t + hh, n0, n1
    a, b = dopri.dense_at(best, Q)
    return t + best * hh, a, b


@njit(cache=True, inline="always")
def _open_steps(S, C, P, rec, vert, H, N, kap_eff, cd_eff, use_taylor):
    """What the steps from the state start with: (room, f0, x_hint, hint, h) — θ̈ at the start (the
    stored one while valid; a Taylor step off θ = 0 needs none), the signs before the switch events and
    the first trial step (:func:`_segment_start`); on ``R_RESUME``, what the loop held when it stopped.
    ``room`` is False when the history is full before its first row (nothing done: NEED_ROOM)."""
    if S[R_RESUME] != 0.0:  # the history was full: go on where the loop stopped
        S[R_RESUME] = 0.0
        return True, S[R_F0], S[R_X_HINT], S[R_HINT], S[R_H]
    t = S[R_T]
    th = S[R_TH]
    thd = S[R_THD]
    if S[R_F0_OK] != 0.0:
        f0 = S[R_F0]
    else:
        want_history = C[C_HISTORY] != 0.0
        if want_history and _hist_full(H, N[N_HISTORY]):
            return False, 0.0, 0.0, 0.0, 0.0
        h_on = S[R_H_ON] != 0.0
        # Taylor steps need no θ̈ at the start; _segment_start reads it only at θ = 0
        f0 = dopri.rhs(t, th, thd, S[R_SIDE], kap_eff, cd_eff, h_on, P, rec, vert) if not use_taylor or th == 0.0 \
            else 0.0
        if want_history:
            N[N_HISTORY] = _write_hist(H, N[N_HISTORY], t, th, thd, _device(S, C),
                                       _ground_at(t, P, rec) if h_on else 0.0)
    x_hint, hint, h = _segment_start(t, th, thd, f0, S[R_SIDE], _events_used(S, C, P)[1], S[R_X_HINT], S[R_HINT],
                                     S[R_H], P, rec)
    return True, f0, x_hint, hint, h


@njit(cache=True, inline="always")
def _trial_step(h, lazy, h_hh, h_err, t, t_next, hmax):
    """The step to try from t towards ``t_next``: the trial step ``h`` — or, when ``lazy``, the step grown
    from the last accepted one (``h_hh`` with error ``h_err``), its power taken only when it may matter
    (:func:`_grows_past`) — cut at ``t_next`` and ``hmax`` and stretched to a known-time event it would
    stop just short of. Returns (hh, h, lazy). [s]"""
    d = min(t_next - t, hmax)
    if lazy and _grows_past(h_hh, h_err, d):
        hh = d  # min(h, t_next - t, hmax) with h >= d
    else:
        if lazy:
            h = _grown_step(h_hh, h_err)
            lazy = False
        hh = min(h, d)
    if t_next - (t + hh) < TIME_TOLERANCE * (1.0 + t):
        hh = t_next - t
    return hh, h, lazy


@njit(cache=True, inline="always")
def _close_steps(S, t, th, thd, f0, f0_ok, h, hint, x_hint, max_abs, steps):
    """Store what the steps leave in the state record (``R_F0_OK``: ``f0`` is θ̈ at t, valid for the next
    segment; ``R_F0`` is also read on ``R_RESUME``)."""
    S[R_T] = t
    S[R_TH] = th
    S[R_THD] = thd
    S[R_F0_OK] = _flag(f0_ok)
    S[R_F0] = f0
    S[R_H] = h
    S[R_HINT] = hint
    S[R_X_HINT] = x_hint
    S[R_MAX_ABS] = max_abs
    S[R_N_STEPS] = steps


@njit(cache=True, **NO_REFCOUNT)
def integrate(S, C, P, rec, vert, K, Q, t_next, queue_times, queue_values, H, N):
    """ROCK: steps towards ``t_next`` — Taylor steps while a record without vertical motion lasts
    (``C_TAYLOR``), Dormand–Prince steps otherwise — each accepted step searched for state events
    (:func:`search_events`); stops at the earliest, located on the step's polynomial. A step ends on
    every known-time event; at a record knot where nothing else happens, and (without a history) at a
    controller sample whose decisions leave the device as it is, the steps go on (to the next
    known-time event) without returning. Returns STEPPED, EVENT, OVERTURNED or NEED_ROOM; past the
    run's budget of steps (``R_N_STEPS`` > ``MAX_STEPS``) it returns STEPPED and the driver ends the run.

    Compiled without reference counting (``core._inline.NO_REFCOUNT``): it allocates nothing. History
    rows go into ``H`` (``N[N_HISTORY]`` written) as far as it has room; when it is full the loop stops
    with NEED_ROOM and ``R_RESUME`` set, the driver grows ``H`` and calls again, and the loop goes on
    exactly where it stopped.
    """
    side = S[R_SIDE]
    h_on = S[R_H_ON] != 0.0
    kap_dev = _device(S, C)
    spring = S[R_SPRING + _working(S)]
    kap_eff = kap_dev * spring
    cd_eff = C[C_CD] * S[R_DAMPER + _working(S)]
    use_taylor = C[C_TAYLOR] != 0.0 and h_on
    want_history = C[C_HISTORY] != 0.0
    # controller samples taken here (what the driver's two passes there would do): not with a history,
    # whose rows the next segment would begin with a row at the sample
    samples_here = C[C_SAMPLED] != 0.0 and not want_history
    seg = segment_events(S, C, P)
    use_xg_event = seg[2]
    inv_g = 1.0 / P[I_G]
    p, sin_alpha, cos_alpha, rtol, atol, hmax = P[I_P], P[I_SINA], P[I_COSA], P[I_RTOL], P[I_ATOL], P[I_HMAX]
    exc_end, alpha, kmax = C[C_EXC_END], P[I_ALPHA], C[C_KMAX]
    room, f0, x_hint, hint, h = _open_steps(S, C, P, rec, vert, H, N, kap_eff, cd_eff, use_taylor)
    if not room:
        return NEED_ROOM
    t, th, thd = S[R_T], S[R_TH], S[R_THD]
    nh = N[N_HISTORY]
    steps = np.int64(S[R_N_STEPS])
    f0_ok = False
    # the trial step h after an accepted step is _grown_step(h_hh, h_err), computed only when needed
    lazy, h_hh, h_err = False, 0.0, 0.0
    max_abs = S[R_MAX_ABS]
    result = STEPPED
    x_at, x_end = -1.0, 0.0  # a Taylor step's Ẍg at its end, x_end, serves the next step starting there
    while True:
        while t < t_next:
            steps += 1
            if steps > MAX_STEPS:
                break  # the driver ends the run
            if want_history and _hist_full(H, nh):
                S[R_RESUME] = 1.0
                S[R_T_NEXT] = t_next
                result = NEED_ROOM
                break
            hh, h, lazy = _trial_step(h, lazy, h_hh, h_err, t, t_next, hmax)
            if hh <= 0.0:
                break
            if use_taylor:
                x0 = x_end if t == x_at else _ground_at(t, P, rec)
                x_at = t + hh
                x_end = ground_acceleration(x_at, P, rec)
                n0, n1, err, f_end = taylor.step(hh, th, thd, side, kap_eff, cd_eff, x0 * inv_g,
                                                 (x_end - x0) * inv_g / hh, p, sin_alpha, cos_alpha, Q, rtol, atol)
            else:
                n0, n1, err = dopri.step(t, hh, th, thd, f0, K, side, kap_eff, cd_eff, h_on, P, rec, vert, rtol, atol)
                f_end = K[6, 1]
            if err > 1.0:
                h = hh * max(0.2, 0.9 * guarded_pow(err, -0.2))
                lazy = False
                continue
            # ---- accepted: look for state events on (t, t + hh] ----
            best, negligible, max_abs = search_events(seg, P, rec, K, Q, t, hh, th, thd, n0, n1, hint, x_hint, max_abs)
            if best < 0.0:
                # left θ = 0 and came back within one step: the excursion is shorter than the step,
                # so resolve it with a smaller one (a zero-length event here would re-uplift at the
                # same instant forever)
                h = 0.25 * hh
                lazy = False
                continue
            if best <= 1.0:  # ---- move to the earliest event ----
                S[R_N_EVENTS] += 1
                t, th, thd = _event_point(best, negligible, t, hh, n0, n1, Q)
                if abs(th) > max_abs:
                    max_abs = abs(th)
                result = EVENT
                break
            # ---- plain accepted step ----
            t = t + hh
            if t_next - t < TIME_TOLERANCE * (1.0 + t):
                t = t_next
                f0_ok = True
            th, thd, f0 = n0, n1, f_end
            if abs(th) > max_abs:
                max_abs = abs(th)
            if want_history:
                nh = _write_hist(H, nh, t, th, thd, kap_dev, _ground_at(t, P, rec) if h_on else 0.0)
            lazy, h_hh, h_err = True, hh, err
            if hint == 0.0 and thd != 0.0:
                hint = sign(thd)
            # early overturning: nothing can bring the block back
            if t >= exc_end and side * th > alpha and side * thd > 0.0 and (spring == 0.0 or kmax == 0.0):
                S[R_T_OVER] = t
                result = OVERTURNED
                break
            if t == t_next and t < exc_end:
                # on a known-time event: when it is only a record knot (the next one lies ahead, so
                # nothing acts here) go on as a new segment would, else leave the step loop
                S[R_T] = t
                t_after = next_known_time(S, C, P, vert, queue_times)
                if t_after > t:
                    t_next = t_after
                    f0_ok = False
                    # _segment_start's cut of h after θ = 0, without the power unless it cuts
                    x_hint, hint, h_cut = _segment_start(t, th, thd, f0, side, use_xg_event, x_hint, hint,
                                                         math.inf if lazy else h, P, rec)
                    if not lazy:
                        h = h_cut
                    elif h_cut < math.inf:
                        h = min(_grown_step(h_hh, h_err), h_cut)
                        lazy = False
        # stopped on a controller sample or decision with nothing else due (no history): take it as the
        # driver's pass would; when it leaves the device, the excitation and the stored θ̈ as they are,
        # the driver's next pass would start the next segment here, so go on (counting both passes).
        # Outside the step loop, whose code stays that of continuous control.
        if not (samples_here and result == STEPPED and t == t_next and t < exc_end and steps < MAX_STEPS):
            break
        S[R_TH] = th
        S[R_THD] = thd
        kap_before, h_before = S[R_KAP_ON], S[R_H_ON]
        known_time_events(S, C, P, rec, queue_times, queue_values)
        steps += 1
        if S[R_KAP_ON] != kap_before or S[R_H_ON] != h_before or S[R_APEX] != 0.0:
            f0_ok = False  # what known_time_events says of θ̈ at t, which closing would overwrite
            break
        steps += 1
        t_after = next_known_time(S, C, P, vert, queue_times)
        if not t_after > t:
            break
        t_next = t_after
        f0_ok = False
        x_hint, hint, h_cut = _segment_start(t, th, thd, f0, side, use_xg_event, x_hint, hint,
                                             math.inf if lazy else h, P, rec)
        if not lazy:
            h = h_cut
        elif h_cut < math.inf:
            h = min(_grown_step(h_hh, h_err), h_cut)
            lazy = False
    if lazy:
        h = _grown_step(h_hh, h_err)
    N[N_HISTORY] = nh
    # a Taylor step's θ̈ at its end comes from its polynomial: the next segment evaluates Eq. (1) anew
    _close_steps(S, t, th, thd, f0, f0_ok and not use_taylor, h, hint, x_hint, max_abs, steps)
    return result


@njit(cache=True, inline=inline_into("drive"))
def state_event(S, C, P, rec, vert):
    """Apply the maps of a located state event: fracture (Eqs. 8–11), overturning, impact
    (Eqs. 14–15: rebound, rest or uplift), the CS01 switch at θ̇ = 0 (an apex decision is due) and
    the CS02 switch at Ẍg = 0. Returns OVERTURNED, IMPACT, IMPACT_UPLIFT, IMPACT_REST or NOTHING."""
    t = S[R_T]
    side = S[R_SIDE]
    if C[C_FRACTURE] != 0.0:
        # only when a working element reaches its ultimate rotation (maps.fracture's own test), so
        # that the other events do not pay for the element views
        sidx = _working(S)
        reach = side * S[R_TH]
        if (S[R_SPRING + sidx] > 0.0 and reach >= P[I_TKU] - ROTATION_TOLERANCE) or \
                (S[R_DAMPER + sidx] > 0.0 and reach >= P[I_TDU] - ROTATION_TOLERANCE):
            maps.fracture(side, S[R_TH], t, S[R_SPRING:R_SPRING + 2], S[R_DAMPER:R_DAMPER + 2],
                          S[R_FRAC:R_FRAC + 4], P[I_TKU], P[I_TDU])
    th = S[R_TH]
    thd = S[R_THD]
    if side * th >= P[I_TOVER] - ROTATION_TOLERANCE:
        S[R_T_OVER] = t
        return OVERTURNED
    use_thd_event, use_xg_event = _events_used(S, C, P)
    if side * th <= IMPACT_TOLERANCE and (side * thd < 0.0 or (thd == 0.0 and th == 0.0)):
        # impact, Eqs. (14)-(15)
        S[R_TH] = 0.0
        S[R_N_IMPACTS] += 1
        xg = _xg(S, P, rec)
        yg = vertical_acceleration(t, P, vert)
        what, side, thd = maps.impact(thd, side, P[I_E], P[I_VREST], xg, yg, P[I_G], P[I_ALPHA])
        S[R_SIDE] = side
        S[R_THD] = thd
        if what == maps.REST:
            S[R_MODE] = MODE_REST
        hint = sign(thd) if thd != 0.0 else side
        S[R_HINT] = hint
        if C[C_SAMPLED] == 0.0 and S[R_MODE] == MODE_ROCK:
            S[R_KAP_ON] = _flag(stiffness_on(int(P[I_STRAT]), side, hint, _sensed(S, P, rec)))
        if what == maps.UPLIFT:
            return IMPACT_UPLIFT
        if what == maps.REST:
            return IMPACT_REST
        return IMPACT
    if use_thd_event and S[R_HINT] * thd <= 0.0:
        S[R_APEX] = 1.0
        S[R_THD] = 0.0
        return NOTHING
    if use_xg_event:
        xg_after = sensed_acceleration(t + 1e-9, P, rec)
        S[R_KAP_ON] = _flag(stiffness_on(int(P[I_STRAT]), side, 0.0, xg_after if xg_after != 0.0 else -S[R_X_HINT]))
    return NOTHING


# ---- the driver -----------------------------------------------------------------------------
@njit(cache=True, inline="always")
def _log_event(what, S, impacts, uplifts, rests, N):
    """Log the time of an impact (and of the uplift or rest it ends in), or of an uplift (``UPLIFTED``)."""
    if what == UPLIFTED:
        N[N_UPLIFTS] = _write_log(uplifts, N[N_UPLIFTS], S[R_T])
        return
    N[N_IMPACTS] = _write_log(impacts, N[N_IMPACTS], S[R_T])
    if what == IMPACT_UPLIFT:
        N[N_UPLIFTS] = _write_log(uplifts, N[N_UPLIFTS], S[R_T])
    if what == IMPACT_REST:
        N[N_RESTS] = _write_log(rests, N[N_RESTS], S[R_T])


@njit(cache=True)
def _room_full(C, H, impacts, uplifts, rests, N):
    """True when the history or an event log the run writes has no more room than its reserve."""
    if C[C_HISTORY] != 0.0 and _hist_full(H, N[N_HISTORY]):
        return True
    return C[C_LOG] != 0.0 and (_log_full(impacts, N[N_IMPACTS]) or _log_full(uplifts, N[N_UPLIFTS])
                                or _log_full(rests, N[N_RESTS]))


@njit(cache=True)
def _history_row(S, C, P, rec, H, N):
    """A row of the history at the state (the caller has made room)."""
    N[N_HISTORY] = _write_hist(H, N[N_HISTORY], S[R_T], S[R_TH], S[R_THD], _device(S, C), _xg(S, P, rec))


@njit(cache=True, **NO_REFCOUNT)
def drive(S, C, P, rec, vert, B, K, Q, queue_times, queue_values, H, impacts, uplifts, rests, N):
    """The driver's loop: the parts of a run in turn until it ends. Returns an ``ST_*`` code, or GROW
    when the history or an event log is full; ``N`` (``N_*``) holds how far each is written.

    Compiled without reference counting (``core._inline.NO_REFCOUNT``), so it allocates nothing: on
    GROW :func:`simulate_kernel` grows the full arrays and calls again. The loop keeps its state in
    ``S`` between passes (and ``integrate`` its own, ``R_RESUME``), so the run goes on where it
    stopped, the same run as with arrays large enough from the start. A run ends as ``ST_ELIMIT``
    past ``MAX_EVENTS`` located events or ``MAX_STEPS`` steps and passes (``R_N_STEPS``)."""
    want_history = C[C_HISTORY] != 0.0
    want_log = C[C_LOG] != 0.0
    while True:
        if S[R_N_EVENTS] > MAX_EVENTS or S[R_N_STEPS] > MAX_STEPS:
            status = ST_ELIMIT
            break
        if _room_full(C, H, impacts, uplifts, rests, N):
            return GROW
        S[R_N_STEPS] += 1.0
        t_next = S[R_T_NEXT] if S[R_RESUME] != 0.0 else next_known_time(S, C, P, vert, queue_times)
        mode = S[R_MODE]
        if want_history and mode != MODE_ROCK:
            _history_row(S, C, P, rec, H, N)
        if mode == MODE_REST or mode == MODE_HOLD:  # on the ground, or held by CS01
            if mode == MODE_REST and S[R_T] >= C[C_EXC_END]:
                status = ST_REST
                break
            if C[C_DRIVEN] != 0.0 and S[R_T] < C[C_EXC_END] and below_driven_bound(S, C, P, B):
                status = ST_BOUND
                break
            if mode == MODE_REST and C[C_QUIET_KNOTS] != 0.0 and S[R_H_ON] != 0.0:
                t_next = pass_quiet_knots(S, C, P, rec, vert, B, queue_times, queue_values, t_next)
            left = ground_phase(S, C, P, rec, vert, t_next)
            if left == UPLIFTED and want_log:
                _log_event(UPLIFTED, S, impacts, uplifts, rests, N)
            if left != NOTHING:
                continue
            # still there at t_next: on to the known-time events there
        if S[R_T] >= t_next:  # a known-time event is due
            if S[R_T] >= C[C_T_STOP]:
                status = ST_TLIM
                break
            known_time_events(S, C, P, rec, queue_times, queue_values)
            continue
        if C[C_BOUND] != 0.0 and S[R_T] >= C[C_EXC_END] and below_overturning_energy(S, C, P):
            status = ST_BOUND
            break
        if C[C_DRIVEN] != 0.0 and S[R_T] < C[C_EXC_END] and below_driven_bound(S, C, P, B):
            status = ST_BOUND
            break
        if S[R_APEX] != 0.0 and apex(S, C, P, rec, vert) == HELD:
            continue
        result = integrate(S, C, P, rec, vert, K, Q, t_next, queue_times, queue_values, H, N)
        if result == NEED_ROOM:
            return GROW
        if result == OVERTURNED:
            status = ST_OVER
            break
        if result == STEPPED:
            continue
        if want_history:
            _history_row(S, C, P, rec, H, N)
        what = state_event(S, C, P, rec, vert)
        S[R_CHECK] = 1.0
        if what == OVERTURNED:
            status = ST_OVER
            break
        if want_log and what >= IMPACT:
            _log_event(what, S, impacts, uplifts, rests, N)
    if want_history:
        _history_row(S, C, P, rec, H, N)
    return status


@njit(cache=True)
def simulate_kernel(P, rec, vert, want_history, want_log):
    """Simulate one run; returns a :class:`~rockstudy.engine._kernel.layout.KernelResult`."""
    return run_kernel(P, rec, vert, driven_bound_data(P, rec, vert), want_history, want_log)


@njit(cache=True, inline="always")
def run_kernel(P, rec, vert, B, want_history, want_log):
    """:func:`simulate_kernel` with the early stop's data ``B`` (:func:`driven_bound_data`) given, so
    that the runs of a threshold scan share it."""
    C = setup(P, vert, want_history, want_log)
    S = initial_state(P, C, rec)
    queue_times, queue_values = maps.queue_new(P[I_DELAY], P[I_TS])
    K = np.zeros((7, 2))
    Q = np.zeros((2, dopri.NQ))
    impacts = np.empty(16 if want_log else 0)
    uplifts = np.empty(16 if want_log else 0)
    rests = np.empty(16 if want_log else 0)
    H = np.empty((256 if want_history else 0, 5))
    N = np.zeros(NFILL, dtype=np.int64)
    while True:
        status = drive(S, C, P, rec, vert, B, K, Q, queue_times, queue_values, H, impacts, uplifts, rests, N)
        if status != GROW:
            break
        if want_history and _hist_full(H, N[N_HISTORY]):
            H = _grow_hist(H, N[N_HISTORY])
        if want_log:
            if _log_full(impacts, N[N_IMPACTS]):
                impacts = _grow_log(impacts, N[N_IMPACTS])
            if _log_full(uplifts, N[N_UPLIFTS]):
                uplifts = _grow_log(uplifts, N[N_UPLIFTS])
            if _log_full(rests, N[N_RESTS]):
                rests = _grow_log(rests, N[N_RESTS])
    return KernelResult(status, S[R_T_OVER], S[R_T], S[R_MAX_ABS], np.int64(S[R_N_IMPACTS]), impacts[:N[N_IMPACTS]],
                        uplifts[:N[N_UPLIFTS]], rests[:N[N_RESTS]], S[R_FRAC:R_FRAC + 4].copy(), H[:N[N_HISTORY]])
