"""Compiled fast engine: event-accurate Dormand–Prince 5(4) integration of the controlled
rocking block (paper Eqs. 1–17), in numba.

Plain floats and arrays only; :mod:`rockstudy.simulate` packs the dataclasses into the
parameter vector ``P`` (indices below). The model and every reading of the paper are
described in ``docs/model.md``; this file follows it item by item.

Integration
-----------
* Dormand–Prince 5(4) with error control (rtol, atol), first-same-as-last, and the
  4th-order continuous extension (Shampine 1986, the one scipy's RK45 uses) to locate state
  events: impacts (θ = 0), overturning, fractures, the CS01 switch (θ̇ = 0) and the CS02
  switch (Ẍg = 0). Events are located by bisection on the interpolant to ~1e-12 of the step.
* Known-time events are never stepped over: the end of the excitation, record knots
  (the ground motion is piecewise linear between samples), controller sample instants and
  actuation instants (t_k + Δτ).
* Three modes: REST (θ = θ̇ = 0, waiting for |Ẍg| > (g + Ÿg)·tanα), ROCK (integration),
  HOLD (the CS01 Filippov sliding state θ̇ = 0, see MODEL-NOTES §1). REST and HOLD exits are
  found by scanning the ground motion (exact per record segment, 1/256 of a period for
  analytic excitations) and bisection.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

# ---- parameter vector layout -------------------------------------------------------
I_P, I_ALPHA, I_G, I_E, I_KMAX, I_KMIN, I_CD, I_TKU, I_TDU, I_TOVER = range(10)
I_STRAT, I_TS, I_DELAY, I_VREST, I_RTOL, I_ATOL, I_FREE = range(10, 17)
I_KIND, I_AMP, I_OMEGA, I_DUR, I_RDT, I_VDT, I_TH0, I_THD0, I_HMAX = range(17, 26)
I_SINA, I_COSA = 26, 27
NPAR = 28

FS, PASSIVE, CS01, CS02 = 0, 1, 2, 3
KIND_ONE_SINE, KIND_MODULATED, KIND_RECORD, KIND_RECTANGULAR = 0, 1, 2, 3
ST_REST, ST_OVER, ST_TLIM, ST_ELIMIT = 0, 1, 2, 3
MODE_REST, MODE_ROCK, MODE_HOLD = 0, 1, 2

MAX_EVENTS = 2_000_000
"""Safety cap on located events per run (a run hitting it returns status ST_ELIMIT)."""
NEGLIGIBLE_STEP = 1e-9
"""[s] An excursion from θ = 0 that returns within a step this short is not resolved further:
the block is taken back on the ground at the step's end (θ = θ̇ = 0)."""

# ---- Dormand–Prince 5(4) tableau ----------------------------------------------------
C2, C3, C4, C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
B1, B3, B4, B5, B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
E1, E3, E4, E5, E6, E7 = -71 / 57600, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40
# continuous extension (scipy RK45.P), rows k1..k7, columns sigma^1..sigma^4
DENSE = np.array([
    [1, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0, 0, 0, 0],
    [0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
    [0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
    [0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
])


# ---- ground motion --------------------------------------------------------------------
@njit(cache=True)
def ground_acceleration(t, P, rec):
    """Horizontal ground acceleration Ẍg(t) while the excitation lasts. [m/s^2]"""
    dur = P[I_DUR]
    if t < 0.0 or t > dur:
        return 0.0
    kind = int(P[I_KIND])
    amp = P[I_AMP]
    if kind == KIND_ONE_SINE:
        return amp * math.sin(P[I_OMEGA] * t)
    if kind == KIND_MODULATED:
        s = t / dur
        return 90.0 * s * s * (s - 1.0) ** 6 * amp * math.sin(P[I_OMEGA] * (t - dur))
    if kind == KIND_RECORD:
        x = t / P[I_RDT]
        i = int(x)
        n = rec.shape[0]
        if i >= n - 1:
            return amp * rec[n - 1]
        f = x - i
        return amp * (rec[i] + f * (rec[i + 1] - rec[i]))
    return amp  # rectangular pulse on [0, dur]


@njit(cache=True)
def vertical_acceleration(t, P, vert):
    """Vertical ground acceleration Ÿg(t), linear between samples, zero outside. [m/s^2]"""
    n = vert.shape[0]
    if n == 0 or t < 0.0:
        return 0.0
    x = t / P[I_VDT]
    i = int(x)
    if i >= n - 1:
        return vert[n - 1] if i == n - 1 and x - i == 0.0 else 0.0
    f = x - i
    return vert[i] + f * (vert[i + 1] - vert[i])


@njit(cache=True)
def _acc(th, thd, side, kap, cd, xg, yg, P):
    """θ̈ of Eq. (1) in normalised form (see rockstudy.motion). [rad/s^2]"""
    p = P[I_P]
    g = P[I_G]
    s = math.sin(th)
    c = math.cos(th)
    sa = side * P[I_SINA]
    ca = P[I_COSA]
    sin_arg = sa * c - ca * s   # sin(side·α − θ)
    cos_arg = ca * c + sa * s   # cos(side·α − θ)
    # cos²(θ/2) = (1 + cos θ)/2
    return -p * p * ((1.0 + yg / g) * sin_arg + (xg / g) * cos_arg + kap * s) - cd * 0.5 * (1.0 + c) * thd


@njit(cache=True)
def _rhs(t, th, thd, side, kap, cd, h_on, P, rec, vert):
    xg = ground_acceleration(t, P, rec) if h_on else 0.0
    yg = vertical_acceleration(t, P, vert)
    return _acc(th, thd, side, kap, cd, xg, yg, P)


@njit(cache=True)
def _dense(sig, h, y0, y1, K):
    """State at t0 + sig·h from the continuous extension."""
    s1 = sig
    s2 = s1 * sig
    s3 = s2 * sig
    s4 = s3 * sig
    a = y0
    b = y1
    for i in range(7):
        w = DENSE[i, 0] * s1 + DENSE[i, 1] * s2 + DENSE[i, 2] * s3 + DENSE[i, 3] * s4
        a += h * w * K[i, 0]
        b += h * w * K[i, 1]
    return a, b


@njit(cache=True)
def _event_value(sig, hh, y0, y1, K, a_th, a_thd, a_x, c, t, P, rec):
    """g = a_th·θ + a_thd·θ̇ + a_x·Ẍg + c at t + sig·hh (Ẍg only when a_x != 0)."""
    a, b = _dense(sig, hh, y0, y1, K)
    g = a_th * a + a_thd * b + c
    if a_x != 0.0:
        g += a_x * ground_acceleration(t + sig * hh, P, rec)
    return g


@njit(cache=True)
def _locate(hi, hh, y0, y1, K, a_th, a_thd, a_x, c, t, P, rec):
    """Earliest sig in (0, hi] where g (positive at 0) reaches <= 0, by the Illinois method.

    Returns -1 when g(hi) > 0 (no crossing before ``hi``). The returned point always has g <= 0.
    """
    fhi = _event_value(hi, hh, y0, y1, K, a_th, a_thd, a_x, c, t, P, rec)
    if fhi > 0.0:
        return -1.0
    lo = 0.0
    flo = _event_value(0.0, hh, y0, y1, K, a_th, a_thd, a_x, c, t, P, rec)
    if flo <= 0.0:
        return hi  # degenerate start on the surface: take the step end
    last = 0
    for _ in range(200):
        if hi - lo <= 1e-13:
            break
        s = hi - fhi * (hi - lo) / (fhi - flo)
        if not (lo < s < hi):
            s = 0.5 * (lo + hi)
        f = _event_value(s, hh, y0, y1, K, a_th, a_thd, a_x, c, t, P, rec)
        if f <= 0.0:
            hi = s
            fhi = f
            if last == -1:
                flo *= 0.5
            last = -1
        else:
            lo = s
            flo = f
            if last == 1:
                fhi *= 0.5
            last = 1
    return hi


@njit(cache=True)
def _sign(x):
    return 1.0 if x > 0 else (-1.0 if x < 0 else 0.0)


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


# ---- control laws (Eqs. 16, 17) -------------------------------------------------------
@njit(cache=True)
def control_on(strategy, theta, theta_dot, xg):
    """True for K_max. CS01: θ·θ̇ ≥ 0 (Eq. 16). CS02: Ẍg·θ ≤ 0 while Ẍg ≠ 0, else CS01 (Eq. 17)."""
    if strategy == CS02 and xg != 0.0:
        return xg * theta <= 0.0
    if strategy == CS01 or strategy == CS02:
        return theta * theta_dot >= 0.0
    return True


# ---- scanning for REST / HOLD exits ---------------------------------------------------
@njit(cache=True)
def _exit_value(mode, t, th, side, kap_max_eff, kap_min_eff, h_on, P, rec, vert):
    """> 0 when the block leaves REST (uplift) or HOLD (either side of the sliding surface)."""
    xg = ground_acceleration(t, P, rec) if h_on else 0.0
    yg = vertical_acceleration(t, P, vert)
    if mode == MODE_REST:
        return abs(xg) - (P[I_G] + yg) * math.tan(P[I_ALPHA])
    a_max = side * _acc(th, 0.0, side, kap_max_eff, 0.0, xg, yg, P)
    a_min = side * _acc(th, 0.0, side, kap_min_eff, 0.0, xg, yg, P)
    return max(a_max, -a_min)  # leave HOLD when s·a_max >= 0 or s·a_min <= 0


@njit(cache=True)
def _scan_exit(mode, t0, t1, th, side, kmx, kmn, h_on, P, rec, vert):
    """First t in (t0, t1] where the exit value becomes >= 0 (> 0 for REST), or -1."""
    kind = int(P[I_KIND])
    if h_on and (kind == KIND_ONE_SINE or kind == KIND_MODULATED):
        dt = 2.0 * math.pi / P[I_OMEGA] / 256.0
    else:
        dt = t1 - t0  # piecewise linear (or constant) on (t0, t1]
    ta = t0
    while ta < t1:
        tb = min(t1, ta + dt)
        if t1 - tb < 1e-12 * dt:
            tb = t1
        vb = _exit_value(mode, tb, th, side, kmx, kmn, h_on, P, rec, vert)
        hit = vb > 0.0 if mode == MODE_REST else vb >= 0.0
        if hit:
            lo = ta
            hi = tb
            for _ in range(80):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                vm = _exit_value(mode, mid, th, side, kmx, kmn, h_on, P, rec, vert)
                if (vm > 0.0) if mode == MODE_REST else (vm >= 0.0):
                    hi = mid
                else:
                    lo = mid
            return hi
        ta = tb
    return -1.0


# ---- the simulation ---------------------------------------------------------------------
@njit(cache=True)
def simulate_kernel(P, rec, vert, want_history, want_log):
    """Simulate one run.

    Returns
    -------
    status, overturn_time, end_time, max_abs_theta, n_impacts,
    impacts, uplifts, rests, fractures (4: spring L, spring R, damper L, damper R; NaN if intact),
    history (n × 5: t, θ, θ̇, κ, Ẍg)
    """
    p = P[I_P]
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

    # state
    t = 0.0
    th = P[I_TH0]
    thd = P[I_THD0]
    h_on = True
    spring = np.ones(2)   # index 0: left (θ > 0), 1: right (θ < 0)
    damper = np.ones(2)
    frac = np.full(4, np.nan)
    kap_on = True          # device state: True → κ_max, False → κ_min
    hint = 0.0             # sign θ̇ will have right after the current instant (CS01 switch event)
    if th != 0.0:
        side = _sign(th)
    elif thd != 0.0:
        side = _sign(thd)
    else:
        side = 1.0
    mode = MODE_ROCK if (th != 0.0 or thd != 0.0) else MODE_REST
    status = ST_TLIM
    t_over = np.nan
    max_abs = abs(th)

    # sampled controller
    k_sample = 0
    nbuf = int(delay / Ts) + 4 if sampled else 1
    pend_t = np.zeros(nbuf)
    pend_v = np.zeros(nbuf, dtype=np.bool_)
    p_head = 0
    p_count = 0

    impacts = np.empty(16 if want_log else 0)
    n_imp = 0
    n_imp_log = 0
    uplifts = np.empty(16 if want_log else 0)
    n_up = 0
    rests = np.empty(16 if want_log else 0)
    n_rest = 0
    H = np.empty((256 if want_history else 0, 5))
    nh = 0

    if not sampled:
        xg0 = ground_acceleration(0.0, P, rec)
        kap_on = control_on(strategy, th, thd, xg0)
        hint = _sign(thd)
    need_apex_decision = continuous_switching and mode == MODE_ROCK and thd == 0.0 and th != 0.0 \
        and (strategy == CS01)

    K = np.zeros((7, 2))
    h = min(1e-3, hmax)
    n_events = 0
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
        if h_on and kind == KIND_RECORD:
            tk = (math.floor(t / P[I_RDT] + 1e-7) + 1.0) * P[I_RDT]
            if tk < t_next:
                t_next = tk
        if nvert > 0 and t < v_end:
            tk = (math.floor(t / P[I_VDT] + 1e-7) + 1.0) * P[I_VDT]
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
        sidx = 0 if side > 0 else 1
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
                t_exit = _scan_exit(mode, t, t_next, th, side, kmax * spring[sidx], kmin * spring[sidx],
                                    h_on, P, rec, vert)
            else:
                t_exit = -1.0
            if t_exit < 0.0:
                t = t_next  # nothing happens before the next known-time event
            else:
                t = t_exit
                n_events += 1
                xg = ground_acceleration(t, P, rec) if h_on else 0.0
                if mode == MODE_REST:
                    side = -_sign(xg)
                    th = 0.0
                    thd = 0.0
                    mode = MODE_ROCK
                    if want_log:
                        uplifts, n_up = _push(uplifts, n_up, t)
                    if not sampled:
                        kap_on = control_on(strategy, side, 0.0, xg)
                    hint = side
                else:
                    yg = vertical_acceleration(t, P, vert)
                    a_max = side * _acc(th, 0.0, side, kmax * spring[sidx], 0.0, xg, yg, P)
                    if a_max >= 0.0:
                        kap_on = True
                        hint = side
                    else:
                        kap_on = False
                        hint = -side
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
            if h_on and t >= h_end:
                h_on = False
                if continuous_switching:
                    kap_on = control_on(strategy, th, thd, 0.0)
                    hint = _sign(thd)
                    if thd == 0.0 and th != 0.0 and mode == MODE_ROCK:
                        need_apex_decision = True
            if sampled:
                while k_sample * Ts <= t + 1e-12:
                    xg = ground_acceleration(t, P, rec) if h_on else 0.0
                    dec = control_on(strategy, th, thd, xg)
                    slot = (p_head + p_count) % nbuf
                    pend_t[slot] = k_sample * Ts + delay
                    pend_v[slot] = dec
                    p_count += 1
                    k_sample += 1
                while p_count > 0 and pend_t[p_head] <= t + 1e-12:
                    kap_on = pend_v[p_head]
                    p_head = (p_head + 1) % nbuf
                    p_count -= 1
            if kap_on != kap_before or h_on != h_before or need_apex_decision:
                f0_ok = False
            continue  # a record knot changes nothing; other events were applied above

        # ---------------- ROCK: apex decision (CS01 switch at θ̇ = 0) ----------------
        if need_apex_decision:
            need_apex_decision = False
            xg = ground_acceleration(t, P, rec) if h_on else 0.0
            yg = vertical_acceleration(t, P, vert)
            a_max = side * _acc(th, 0.0, side, kmax * spring[sidx], 0.0, xg, yg, P)
            a_min = side * _acc(th, 0.0, side, kmin * spring[sidx], 0.0, xg, yg, P)
            thd = 0.0
            if a_max >= 0.0:
                kap_on = True
                hint = side
            elif a_min <= 0.0:
                kap_on = False
                hint = -side
            else:
                mode = MODE_HOLD
                continue
            kap_dev = kmax if kap_on else kmin
            kap_eff = kap_dev * spring[sidx]

        # ---------------- ROCK: integrate towards t_next ----------------
        use_thd_event = continuous_switching and (strategy == CS01 or not h_on)
        use_xg_event = continuous_switching and strategy == CS02 and h_on
        if f0_ok:
            f0 = f0_saved
        else:
            f0 = _rhs(t, th, thd, side, kap_eff, cd_eff, h_on, P, rec, vert)
            if want_history:
                H, nh = _push_hist(H, nh, t, th, thd, kap_dev, ground_acceleration(t, P, rec) if h_on else 0.0)
        f0_ok = False
        if use_xg_event:
            xs = ground_acceleration(t, P, rec)
            if xs == 0.0:
                xs = ground_acceleration(t + 1e-9, P, rec)
            x_hint = _sign(xs)
        if thd != 0.0:
            hint = _sign(thd)
        # after an impact or uplift (θ = 0) keep the first step inside the excursion
        if th == 0.0 and side * f0 < 0.0 and side * thd > 0.0:
            h = min(h, 0.5 * abs(thd / f0))
        event_found = False
        while t < t_next:
            hh = min(h, t_next - t, hmax)
            if t_next - (t + hh) < 1e-12 * (1.0 + t):
                hh = t_next - t
            if hh <= 0.0:
                break
            y0 = th
            y1 = thd
            K[0, 0] = y1
            K[0, 1] = f0
            a0 = y0 + hh * A21 * K[0, 0]
            a1 = y1 + hh * A21 * K[0, 1]
            K[1, 0] = a1
            K[1, 1] = _rhs(t + C2 * hh, a0, a1, side, kap_eff, cd_eff, h_on, P, rec, vert)
            a0 = y0 + hh * (A31 * K[0, 0] + A32 * K[1, 0])
            a1 = y1 + hh * (A31 * K[0, 1] + A32 * K[1, 1])
            K[2, 0] = a1
            K[2, 1] = _rhs(t + C3 * hh, a0, a1, side, kap_eff, cd_eff, h_on, P, rec, vert)
            a0 = y0 + hh * (A41 * K[0, 0] + A42 * K[1, 0] + A43 * K[2, 0])
            a1 = y1 + hh * (A41 * K[0, 1] + A42 * K[1, 1] + A43 * K[2, 1])
            K[3, 0] = a1
            K[3, 1] = _rhs(t + C4 * hh, a0, a1, side, kap_eff, cd_eff, h_on, P, rec, vert)
            a0 = y0 + hh * (A51 * K[0, 0] + A52 * K[1, 0] + A53 * K[2, 0] + A54 * K[3, 0])
            a1 = y1 + hh * (A51 * K[0, 1] + A52 * K[1, 1] + A53 * K[2, 1] + A54 * K[3, 1])
            K[4, 0] = a1
            K[4, 1] = _rhs(t + C5 * hh, a0, a1, side, kap_eff, cd_eff, h_on, P, rec, vert)
            a0 = y0 + hh * (A61 * K[0, 0] + A62 * K[1, 0] + A63 * K[2, 0] + A64 * K[3, 0] + A65 * K[4, 0])
            a1 = y1 + hh * (A61 * K[0, 1] + A62 * K[1, 1] + A63 * K[2, 1] + A64 * K[3, 1] + A65 * K[4, 1])
            K[5, 0] = a1
            K[5, 1] = _rhs(t + hh, a0, a1, side, kap_eff, cd_eff, h_on, P, rec, vert)
            n0 = y0 + hh * (B1 * K[0, 0] + B3 * K[2, 0] + B4 * K[3, 0] + B5 * K[4, 0] + B6 * K[5, 0])
            n1 = y1 + hh * (B1 * K[0, 1] + B3 * K[2, 1] + B4 * K[3, 1] + B5 * K[4, 1] + B6 * K[5, 1])
            K[6, 0] = n1
            K[6, 1] = _rhs(t + hh, n0, n1, side, kap_eff, cd_eff, h_on, P, rec, vert)
            e0 = hh * (E1 * K[0, 0] + E3 * K[2, 0] + E4 * K[3, 0] + E5 * K[4, 0] + E6 * K[5, 0] + E7 * K[6, 0])
            e1 = hh * (E1 * K[0, 1] + E3 * K[2, 1] + E4 * K[3, 1] + E5 * K[4, 1] + E6 * K[5, 1] + E7 * K[6, 1])
            s0 = atol + rtol * max(abs(y0), abs(n0))
            s1 = atol + rtol * max(abs(y1), abs(n1))
            err = math.sqrt(0.5 * ((e0 / s0) ** 2 + (e1 / s1) ** 2))
            if err > 1.0:
                h = hh * max(0.2, 0.9 * err ** -0.2)
                continue
            # ---- accepted: look for state events on (t, t + hh] ----
            best = 2.0
            negligible = False
            # impact: side·θ crosses to <= 0
            if side * n0 <= 0.0:
                if side * y0 > 0.0:
                    best = _locate(1.0, hh, y0, y1, K, side, 0.0, 0.0, 0.0, t, P, rec)
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
                sa_ = _locate(1.0, hh, y0, y1, K, 0.0, side, 0.0, 0.0, t, P, rec)
                if sa_ >= 0.0:
                    a, b = _dense(sa_, hh, y0, y1, K)
                    if side * a > peak:
                        peak = side * a
                        sig_peak = sa_
                    if abs(a) > max_abs:
                        max_abs = abs(a)
            if not negligible and peak - th_over >= 0.0 and side * y0 - th_over < 0.0:
                s = _locate(min(best, sig_peak), hh, y0, y1, K, -side, 0.0, 0.0, th_over, t, P, rec)
                if s >= 0.0:
                    best = s
            if track_fracture:
                for k in range(2):
                    thu = th_ku if k == 0 else th_du
                    intact = spring[sidx] if k == 0 else damper[sidx]
                    if not negligible and intact > 0.0 and side * y0 - thu < 0.0 and peak - thu >= 0.0:
                        s = _locate(min(best, sig_peak), hh, y0, y1, K, -side, 0.0, 0.0, thu, t, P, rec)
                        if s >= 0.0:
                            best = s
            if not negligible and use_thd_event and hint != 0.0 and hint * n1 <= 0.0:
                s = _locate(min(best, 1.0), hh, y0, y1, K, 0.0, hint, 0.0, 0.0, t, P, rec)
                if s >= 0.0:
                    best = s
            if not negligible and use_xg_event and x_hint != 0.0:
                if x_hint * ground_acceleration(t + hh, P, rec) <= 0.0:
                    s = _locate(min(best, 1.0), hh, y0, y1, K, 0.0, 0.0, x_hint, 0.0, t, P, rec)
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
                    a, b = _dense(best, hh, y0, y1, K)
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
            if t_next - t < 1e-12 * (1.0 + t):
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
                hint = _sign(thd)
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
            if spring[sidx] > 0.0 and side * th >= th_ku - 1e-12:
                spring[sidx] = 0.0
                frac[sidx] = t
            if damper[sidx] > 0.0 and side * th >= th_du - 1e-12:
                damper[sidx] = 0.0
                frac[2 + sidx] = t
        if side * th >= th_over - 1e-12:
            status = ST_OVER
            t_over = t
            break
        if side * th <= 1e-14 and (side * thd < 0.0 or (thd == 0.0 and th == 0.0)):
            # impact, Eq. (14)
            th = 0.0
            v_after = e * thd
            n_imp += 1
            if want_log:
                impacts, n_imp_log = _push(impacts, n_imp_log, t)
            xg = ground_acceleration(t, P, rec) if h_on else 0.0
            if abs(v_after) < v_rest:
                yg = vertical_acceleration(t, P, vert)
                if abs(xg) > (P[I_G] + yg) * math.tan(alpha):
                    side = -_sign(xg)
                    thd = 0.0
                    if want_log:
                        uplifts, n_up = _push(uplifts, n_up, t)
                else:
                    thd = 0.0
                    mode = MODE_REST
                    if want_log:
                        rests, n_rest = _push(rests, n_rest, t)
            else:
                side = -side
                thd = v_after
            hint = _sign(thd) if thd != 0.0 else side
            if not sampled and mode == MODE_ROCK:
                kap_on = control_on(strategy, side, hint, xg)
            continue
        if use_thd_event and hint * thd <= 0.0:
            need_apex_decision = True
            thd = 0.0
            continue
        if use_xg_event:
            xg_after = ground_acceleration(t + 1e-9, P, rec)
            kap_on = control_on(strategy, side, 0.0, xg_after if xg_after != 0.0 else -x_hint)
            continue

    if want_history:
        H, nh = _push_hist(H, nh, t, th, thd, kmax if kap_on else kmin,
                           ground_acceleration(t, P, rec) if h_on else 0.0)
    return (status, t_over, t, max_abs, n_imp, impacts[:n_imp_log], uplifts[:n_up], rests[:n_rest],
            frac, H[:nh])


# ---- threshold search -----------------------------------------------------------------
@njit(cache=True)
def outcome_kernel(P, rec, vert, amplitude_ratio, unit_peak):
    """Outcome at one amplitude ratio: 0 cannot uplift (skipped), 1 safe, 2 overturned without
    impact, 3 overturned after at least one impact, 4 event limit."""
    if vert.shape[0] == 0 and amplitude_ratio * unit_peak <= 1.0:
        return 0
    Q = P.copy()
    Q[I_AMP] = amplitude_ratio * P[I_G] * math.tan(P[I_ALPHA])
    res = simulate_kernel(Q, rec, vert, False, False)
    status = res[0]
    if status == ST_ELIMIT:
        return 4
    if status == ST_OVER:
        return 3 if res[4] > 0 else 2
    return 1


@njit(cache=True)
def threshold_kernel(P, rec, vert, grid, resolution, unit_peak):
    """Lowest overturning amplitude ratio: scan ``grid`` upward, then bisect between the last
    safe and the first overturning grid point until the bracket is <= resolution.

    Returns (threshold, lower_safe, n_simulations, n_undetermined); threshold = NaN when nothing
    on the grid overturns. An undetermined run (outcome 4, event cap) counts as not overturned
    and is counted, so that callers can report it.
    """
    n_sim = 0
    n_und = 0
    lower = 0.0
    if vert.shape[0] == 0 and unit_peak > 0:
        lower = 1.0 / unit_peak  # below this the record cannot uplift the block
    for j in range(grid.shape[0]):
        a = grid[j]
        o = outcome_kernel(P, rec, vert, a, unit_peak)
        if o != 0:
            n_sim += 1
        if o == 4:
            n_und += 1
        if o == 2 or o == 3:  # 4 (event cap) is undetermined, not overturned
            hi = a
            lo = grid[j - 1] if j > 0 else lower
            if lo < lower:
                lo = lower
            while hi - lo > resolution:
                mid = 0.5 * (lo + hi)
                om = outcome_kernel(P, rec, vert, mid, unit_peak)
                if om != 0:
                    n_sim += 1
                if om == 4:
                    n_und += 1
                if om == 2 or om == 3:
                    hi = mid
                else:
                    lo = mid
            return hi, lo, n_sim, n_und
    return np.nan, grid[grid.shape[0] - 1], n_sim, n_und


@njit(cache=True, parallel=True)
def threshold_batch(Pm, recs, rec_off, rec_len, vert, grid, resolution, peaks):
    """threshold_kernel over many cases (rows of Pm), in parallel."""
    n = Pm.shape[0]
    out = np.empty(n)
    low = np.empty(n)
    nsim = np.zeros(n, dtype=np.int64)
    nund = np.zeros(n, dtype=np.int64)
    for i in prange(n):
        rec = recs[rec_off[i]:rec_off[i] + rec_len[i]]
        th, lo, ns, nu = threshold_kernel(Pm[i], rec, vert, grid, resolution, peaks[i])
        out[i] = th
        low[i] = lo
        nsim[i] = ns
        nund[i] = nu
    return out, low, nsim, nund


@njit(cache=True, parallel=True)
def outcome_batch(Pm, recs, rec_off, rec_len, vert, grid, peaks):
    """outcome_kernel on the full (case × amplitude) grid, in parallel over cases."""
    n = Pm.shape[0]
    m = grid.shape[0]
    out = np.zeros((n, m), dtype=np.int8)
    for i in prange(n):
        rec = recs[rec_off[i]:rec_off[i] + rec_len[i]]
        for j in range(m):
            out[i, j] = outcome_kernel(Pm[i], rec, vert, grid[j], peaks[i])
    return out
