"""The driving loop of the fast engine (paper §3): between known-time events (the end of the
excitation, record knots, controller samples and actuation instants) the block is at REST, HOLD
or ROCKs under Dormand–Prince steps; each accepted step is searched for state events, the
earliest is located and its map applied.

The model and every reading of the paper are in ``docs/model.md``.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..constants import FIRST_STEP, IMPACT_TOLERANCE, MAX_EVENTS, NEGLIGIBLE_STEP, ROTATION_TOLERANCE, TIME_TOLERANCE
from ..control import CS01, CS02, FS, PASSIVE, stiffness_on
from ..excitation import RECORD
from . import dopri, maps
from .events import locate, scan_exit
from .ground import ground_acceleration, vertical_acceleration
from .layout import (
    I_ALPHA,
    I_ATOL,
    I_BOUND,
    I_CD,
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
    I_STRAT,
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
    RIGHT,
    ST_BOUND,
    ST_ELIMIT,
    ST_OVER,
    ST_REST,
    ST_TLIM,
    KernelResult,
)
from .maps import sign


# ---- growable logs --------------------------------------------------------------------
@njit(cache=True)
def _push(arr, n, v):
    if n >= arr.shape[0]:
        new = np.empty(max(16, 2 * arr.shape[0]))
        new[:n] = arr[:n]
        arr = new
    arr[n] = v
    return arr, n + 1


@njit(cache=True)
def _push_hist(H, n, t, th, thd, kap, xg):
    if n >= H.shape[0]:
        new = np.empty((max(256, 2 * H.shape[0]), 5))
        new[:n] = H[:n]
        H = new
    H[n, 0] = t
    H[n, 1] = th
    H[n, 2] = thd
    H[n, 3] = kap
    H[n, 4] = xg
    return H, n + 1


@njit(cache=True)
def _next_knot(t, dt):
    """The sampling instant after t of a record sampled every dt. [s]"""
    return (math.floor(t / dt + 1e-7) + 1.0) * dt


@njit(cache=True)
def simulate_kernel(P, rec, vert, want_history, want_log):
    """Simulate one run; returns a :class:`~rockstudy._kernel.layout.KernelResult`."""
    alpha = P[I_ALPHA]
    e = P[I_E]
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
    th_ku = P[I_TKU]
    th_du = P[I_TDU]
    th_over = P[I_TOVER]
    Ts = P[I_TS]
    delay = P[I_DELAY]
    sampled = Ts > 0.0
    continuous_switching = (not sampled) and (strategy == CS01 or strategy == CS02) and kmax != kmin
    v_rest = P[I_VREST]
    rtol = P[I_RTOL]
    atol = P[I_ATOL]
    hmax = P[I_HMAX]
    kind = int(P[I_KIND])
    h_end = P[I_DUR]
    nvert = vert.shape[0]
    v_end = (nvert - 1) * P[I_VDT] if nvert > 0 else 0.0
    exc_end = max(h_end, v_end)
    t_stop = exc_end + P[I_FREE]
    track_fracture = strategy != FS and (kmax > 0.0 or cdamp > 0.0)
    # end the run once it provably cannot overturn any more (outcome runs, continuous control only)
    energy_bound = P[I_BOUND] != 0.0 and not want_history and not want_log
    # with sampled control a stale K_max can give energy back: a weaker bound over half-cycles
    switching_bound = sampled and kmax != kmin

    # state (counters start as np.int64(0) and flags as comparisons: a literal 0 or True would make
    # numba compile every callee once more for the literal type, for nothing)
    t = 0.0
    th = P[I_TH0]
    thd = P[I_THD0]
    h_on = t == 0.0   # True; written as a comparison, so that numba types it bool, not Literal[True]
    spring = np.ones(2)   # intact flags by corner (LEFT works for θ > 0, RIGHT for θ < 0)
    damper = np.ones(2)
    frac = np.full(4, np.nan)
    kap_on = True          # device state: True → κ_max, False → κ_min
    hint = 0.0             # sign θ̇ will have right after the current instant (CS01 switch event)
    if th != 0.0:
        side = sign(th)
    elif thd != 0.0:
        side = sign(thd)
    else:
        side = 1.0
    mode = MODE_ROCK if (th != 0.0 or thd != 0.0) else MODE_REST
    status = ST_TLIM
    t_over = np.nan
    max_abs = abs(th)

    # sampled controller: decision k is taken at k·T_s and acts from k·T_s + Δτ
    k_sample = np.int64(0)
    pend_t, pend_v = maps.queue_new(delay, Ts)
    nbuf = pend_t.shape[0]
    p_head = np.int64(0)
    p_count = np.int64(0)

    impacts = np.empty(16 if want_log else 0)
    n_imp = np.int64(0)
    n_imp_log = np.int64(0)
    uplifts = np.empty(16 if want_log else 0)
    n_up = np.int64(0)
    rests = np.empty(16 if want_log else 0)
    n_rest = np.int64(0)
    H = np.empty((256 if want_history else 0, 5))
    nh = np.int64(0)

    if not sampled:
        xg0 = ground_acceleration(0.0, P, rec)
        kap_on = stiffness_on(strategy, th, thd, xg0)
        hint = sign(thd)
    need_apex_decision = continuous_switching and mode == MODE_ROCK and thd == 0.0 and th != 0.0 \
        and (strategy == CS01)

    K = np.zeros((7, 2))
    h = min(FIRST_STEP, hmax)
    n_events = np.int64(0)
    x_hint = 0.0
    f0_ok = False       # FSAL derivative still valid across a known-time event that changed nothing
    f0_saved = 0.0

    while True:
        if n_events > MAX_EVENTS:
            status = ST_ELIMIT
            break
        # ---------------- next known-time event ----------------
        t_next = t_stop
        if h_on and h_end < t_next:
            t_next = max(h_end, t)
        if h_on and kind == RECORD:  # Ẍg is linear between knots: steps end at each
            tk = _next_knot(t, P[I_RDT])
            if tk < t_next:
                t_next = tk
        if nvert > 0 and t < v_end:
            tk = _next_knot(t, P[I_VDT])
            if tk < t_next:
                t_next = tk
        if sampled:
            ts_ = k_sample * Ts
            if ts_ < t_next:
                t_next = ts_
            if p_count > 0 and pend_t[p_head] < t_next:
                t_next = pend_t[p_head]
        if t_next < t:
            t_next = t

        # working-side element flags and stiffness
        sidx = LEFT if side > 0 else RIGHT
        kap_dev = kmax if kap_on else kmin
        kap_eff = kap_dev * spring[sidx]
        cd_eff = cdamp * damper[sidx]

        if want_history and mode != MODE_ROCK:
            H, nh = _push_hist(H, nh, t, th, thd, kap_dev,
                               ground_acceleration(t, P, rec) if h_on else 0.0)

        # ---------------- REST / HOLD ----------------
        if mode == MODE_REST or mode == MODE_HOLD:
            if mode == MODE_REST and t >= exc_end:
                status = ST_REST
                break
            if t_next > t:
                t_exit = scan_exit(mode, t, t_next, th, side, kmax * spring[sidx], kmin * spring[sidx],
                                   h_on, P, rec, vert)
            else:
                t_exit = -1.0
            if t_exit < 0.0:
                t = t_next  # nothing happens before the next known-time event
            else:
                t = t_exit
                n_events += 1
                xg = ground_acceleration(t, P, rec) if h_on else 0.0
                if mode == MODE_REST:  # uplift
                    side = maps.uplift_side(xg)
                    th = 0.0
                    thd = 0.0
                    mode = MODE_ROCK
                    if want_log:
                        uplifts, n_up = _push(uplifts, n_up, t)
                    if not sampled:
                        kap_on = stiffness_on(strategy, side, 0.0, xg)
                    hint = side
                else:  # leaves the sliding surface, outward or back (never HOLD again here)
                    yg = vertical_acceleration(t, P, vert)
                    turn = maps.apex_decision(th, side, kmax * spring[sidx], kmin * spring[sidx], xg, yg, P)
                    kap_on = turn == maps.TURN_OUT
                    hint = side if kap_on else -side
                    mode = MODE_ROCK
                    thd = 0.0
                continue
        # ---------------- known-time events at t ----------------
        if t >= t_next:
            if t >= t_stop:
                status = ST_TLIM
                break
            kap_before = kap_on
            h_before = h_on
            if h_on and t >= h_end:  # the excitation ends
                h_on = False
                if continuous_switching:
                    kap_on = stiffness_on(strategy, th, thd, 0.0)
                    hint = sign(thd)
                    if thd == 0.0 and th != 0.0 and mode == MODE_ROCK:
                        need_apex_decision = True
            if sampled:
                while k_sample * Ts <= t + TIME_TOLERANCE:  # controller samples due
                    xg = ground_acceleration(t, P, rec) if h_on else 0.0
                    p_count = maps.queue_push(pend_t, pend_v, p_head, p_count, k_sample * Ts + delay,
                                              stiffness_on(strategy, th, thd, xg))
                    k_sample += 1
                while p_count > 0 and pend_t[p_head] <= t + TIME_TOLERANCE:  # decisions that act now
                    kap_on = pend_v[p_head]
                    p_head = (p_head + 1) % nbuf
                    p_count -= 1
            if kap_on != kap_before or h_on != h_before or need_apex_decision:
                f0_ok = False
            continue  # a record knot changes nothing; other events were applied above

        # ---------------- ROCK: below the overturning energy after the excitation? ----------------
        if energy_bound and t >= exc_end:
            if switching_bound:
                stop = maps.cannot_overturn_switching(th, thd, side, P[I_P], alpha, e, kmax)
            else:
                stop = maps.cannot_overturn(th, thd, P[I_P], alpha, kmin * spring[sidx])
            if stop:
                status = ST_BOUND
                break

        # ---------------- ROCK: apex decision (CS01 switch at θ̇ = 0) ----------------
        if need_apex_decision:
            need_apex_decision = False
            xg = ground_acceleration(t, P, rec) if h_on else 0.0
            yg = vertical_acceleration(t, P, vert)
            turn = maps.apex_decision(th, side, kmax * spring[sidx], kmin * spring[sidx], xg, yg, P)
            thd = 0.0
            if turn == maps.HOLD:
                mode = MODE_HOLD
                continue
            kap_on = turn == maps.TURN_OUT
            hint = side if kap_on else -side
            kap_dev = kmax if kap_on else kmin
            kap_eff = kap_dev * spring[sidx]

        # ---------------- ROCK: integrate towards t_next ----------------
        use_thd_event = continuous_switching and (strategy == CS01 or not h_on)
        use_xg_event = continuous_switching and strategy == CS02 and h_on
        if f0_ok:
            f0 = f0_saved
        else:
            f0 = dopri.rhs(t, th, thd, side, kap_eff, cd_eff, h_on, P, rec, vert)
            if want_history:
                H, nh = _push_hist(H, nh, t, th, thd, kap_dev, ground_acceleration(t, P, rec) if h_on else 0.0)
        f0_ok = False
        if use_xg_event:
            xs = ground_acceleration(t, P, rec)
            if xs == 0.0:
                xs = ground_acceleration(t + 1e-9, P, rec)
            x_hint = sign(xs)
        if thd != 0.0:
            hint = sign(thd)
        # after an impact or uplift (θ = 0) keep the first step inside the excursion
        if th == 0.0 and side * f0 < 0.0 and side * thd > 0.0:
            h = min(h, 0.5 * abs(thd / f0))
        event_found = False
        while t < t_next:
            hh = min(h, t_next - t, hmax)
            if t_next - (t + hh) < TIME_TOLERANCE * (1.0 + t):
                hh = t_next - t
            if hh <= 0.0:
                break
            y0 = th
            y1 = thd
            n0, n1, err = dopri.step(t, hh, y0, y1, f0, K, side, kap_eff, cd_eff, h_on, P, rec, vert, rtol, atol)
            if err > 1.0:
                h = hh * max(0.2, 0.9 * err ** -0.2)
                continue
            # ---- accepted: look for state events on (t, t + hh] ----
            best = 2.0
            negligible = False
            # impact: side·θ crosses to <= 0
            if side * n0 <= 0.0:
                if side * y0 > 0.0:
                    best = locate(1.0, hh, y0, y1, K, side, 0.0, 0.0, 0.0, t, P, rec)
                elif hh > NEGLIGIBLE_STEP:
                    # left θ = 0 and came back within one step: the excursion is shorter than
                    # the step, so resolve it with a smaller one (a zero-length event here
                    # would re-uplift at the same instant forever)
                    h = 0.25 * hh
                    continue
                else:
                    negligible = True  # an excursion shorter than NEGLIGIBLE_STEP: it ends at t + hh
                    best = 1.0
            # an apex inside the step: the largest rotation may lie between the step ends, and a
            # rotation threshold may be crossed and re-crossed within the step (grazing)
            peak = side * n0
            sig_peak = 1.0
            if not negligible and side * y1 > 0.0 and side * n1 <= 0.0:
                sa_ = locate(1.0, hh, y0, y1, K, 0.0, side, 0.0, 0.0, t, P, rec)
                if sa_ >= 0.0:
                    a, b = dopri.dense(sa_, hh, y0, y1, K)
                    if side * a > peak:
                        peak = side * a
                        sig_peak = sa_
                    if abs(a) > max_abs:
                        max_abs = abs(a)
            if not negligible and peak - th_over >= 0.0 and side * y0 - th_over < 0.0:
                s = locate(min(best, sig_peak), hh, y0, y1, K, -side, 0.0, 0.0, th_over, t, P, rec)
                if s >= 0.0:
                    best = s
            if track_fracture:
                for k in range(2):
                    thu = th_ku if k == 0 else th_du
                    intact = spring[sidx] if k == 0 else damper[sidx]
                    if not negligible and intact > 0.0 and side * y0 - thu < 0.0 and peak - thu >= 0.0:
                        s = locate(min(best, sig_peak), hh, y0, y1, K, -side, 0.0, 0.0, thu, t, P, rec)
                        if s >= 0.0:
                            best = s
            if not negligible and use_thd_event and hint != 0.0 and hint * n1 <= 0.0:
                s = locate(min(best, 1.0), hh, y0, y1, K, 0.0, hint, 0.0, 0.0, t, P, rec)
                if s >= 0.0:
                    best = s
            if not negligible and use_xg_event and x_hint != 0.0:
                if x_hint * ground_acceleration(t + hh, P, rec) <= 0.0:
                    s = locate(min(best, 1.0), hh, y0, y1, K, 0.0, 0.0, x_hint, 0.0, t, P, rec)
                    if s >= 0.0:
                        best = s
            if best <= 1.0:
                # ---- move to the earliest event and apply every change that holds there ----
                n_events += 1
                if negligible:
                    a = 0.0
                    b = 0.0
                    tev = t + hh
                else:
                    a, b = dopri.dense(best, hh, y0, y1, K)
                    tev = t + best * hh
                    if best == 1.0:
                        a, b = n0, n1
                        tev = t + hh
                t = tev
                th = a
                thd = b
                if abs(th) > max_abs:
                    max_abs = abs(th)
                event_found = True
                break
            # ---- plain accepted step ----
            t = t + hh
            if t_next - t < TIME_TOLERANCE * (1.0 + t):
                t = t_next
                f0_ok = True
                f0_saved = K[6, 1]
            th = n0
            thd = n1
            f0 = K[6, 1]
            if abs(th) > max_abs:
                max_abs = abs(th)
            if want_history:
                H, nh = _push_hist(H, nh, t, th, thd, kap_dev,
                                   ground_acceleration(t, P, rec) if h_on else 0.0)
            h = hh * min(10.0, 0.9 * err ** -0.2) if err > 0 else hh * 10.0
            if hint == 0.0 and thd != 0.0:
                hint = sign(thd)
            # early overturning: nothing can bring the block back
            if t >= exc_end and side * th > alpha and side * thd > 0.0 and (spring[sidx] == 0.0 or kmax == 0.0):
                status = ST_OVER
                t_over = t
                break
        if status == ST_OVER:
            break
        if not event_found:
            continue

        # ---------------- state events at (t, th, thd) ----------------
        if want_history:
            H, nh = _push_hist(H, nh, t, th, thd, kap_dev, ground_acceleration(t, P, rec) if h_on else 0.0)
        if track_fracture:
            maps.fracture(side, th, t, spring, damper, frac, th_ku, th_du)
        if side * th >= th_over - ROTATION_TOLERANCE:
            status = ST_OVER
            t_over = t
            break
        if side * th <= IMPACT_TOLERANCE and (side * thd < 0.0 or (thd == 0.0 and th == 0.0)):
            # impact, Eqs. (14)-(15)
            th = 0.0
            n_imp += 1
            if want_log:
                impacts, n_imp_log = _push(impacts, n_imp_log, t)
            xg = ground_acceleration(t, P, rec) if h_on else 0.0
            yg = vertical_acceleration(t, P, vert)
            what, side, thd = maps.impact(thd, side, e, v_rest, xg, yg, P[I_G], alpha)
            if what == maps.UPLIFT and want_log:
                uplifts, n_up = _push(uplifts, n_up, t)
            if what == maps.REST:
                mode = MODE_REST
                if want_log:
                    rests, n_rest = _push(rests, n_rest, t)
            hint = sign(thd) if thd != 0.0 else side
            if not sampled and mode == MODE_ROCK:
                kap_on = stiffness_on(strategy, side, hint, xg)
            continue
        if use_thd_event and hint * thd <= 0.0:
            need_apex_decision = True
            thd = 0.0
            continue
        if use_xg_event:
            xg_after = ground_acceleration(t + 1e-9, P, rec)
            kap_on = stiffness_on(strategy, side, 0.0, xg_after if xg_after != 0.0 else -x_hint)
            continue

    if want_history:
        H, nh = _push_hist(H, nh, t, th, thd, kmax if kap_on else kmin,
                           ground_acceleration(t, P, rec) if h_on else 0.0)
    return KernelResult(status, t_over, t, max_abs, n_imp, impacts[:n_imp_log], uplifts[:n_up], rests[:n_rest],
                        frac, H[:nh])
