"""Event detection and location: zeros of g = a_θ·θ + a_θ̇·θ̇ + a_x·Ẍg + c on a step's continuous
extension (impacts, rotation thresholds, the CS01 and CS02 switches), and the exits from REST and
HOLD found by scanning the ground motion.

The a_x·Ẍg term is the CS02 switch, a decision of the controller: it reads Ẍg as the controller
senses it (:func:`rockstudy.engine._kernel.ground.sensed_acceleration`). The REST and HOLD exits concern
the block, so they read the driving Ẍg."""
from __future__ import annotations

import math

import numpy as np

from rockstudy.core._inline import NO_REFCOUNT, inline_into, njit
from rockstudy.core.constants import LOCATE_TOLERANCE
from rockstudy.engine._kernel.dopri import acceleration
from rockstudy.engine._kernel.ground import ground_acceleration, sensed_acceleration, vertical_acceleration
from rockstudy.engine._kernel.layout import I_ALPHA, I_G, I_KIND, I_OMEGA, MODE_REST
from rockstudy.model.excitation import MODULATED, ONE_SINE

_NONE = np.zeros(0)

REST_HOLD_SCAN_DIVISIONS = 256.0
"""An analytic excitation's period is scanned in this many pieces for a REST/HOLD exit (a root of a
smooth function cannot hide inside 1/256 of a period at the amplitudes that matter)."""


@njit(cache=True, inline="always")
def event_poly(Q, a_th, a_thd, c):
    """The coefficients (g0 … g6) of g = a_th·θ + a_thd·θ̇ + c on a Taylor step, a polynomial of degree 6
    in the fraction of the step, from the step's polynomials ``Q`` (:mod:`~rockstudy.engine._kernel.taylor`)."""
    return (a_th * Q[0, 0] + a_thd * Q[1, 0] + c, a_th * Q[0, 1] + a_thd * Q[1, 1], a_th * Q[0, 2] + a_thd * Q[1, 2],
            a_th * Q[0, 3] + a_thd * Q[1, 3], a_th * Q[0, 4] + a_thd * Q[1, 4], a_th * Q[0, 5] + a_thd * Q[1, 5],
            a_th * Q[0, 6] + a_thd * Q[1, 6])


@njit(cache=True, inline="always")
def _poly_at(sig, g0, g1, g2, g3, g4, g5, g6):
    """g at sig by Horner (degree 6; a quartic's g5 = g6 = 0 give the quartic's Horner values exactly)."""
    v = (g6 * sig + g5) * sig + g4
    return (((v * sig + g3) * sig + g2) * sig + g1) * sig + g0


@njit(cache=True, inline="always")
def _poly_and_slope(sig, g0, g1, g2, g3, g4, g5, g6):
    """g and dg/dsig at sig (two Horner chains side by side), of degree 6 as :func:`_poly_at`."""
    v = (g6 * sig + g5) * sig + g4
    w = (6.0 * g6 * sig + 5.0 * g5) * sig + 4.0 * g4
    f = (((v * sig + g3) * sig + g2) * sig + g1) * sig + g0
    d = ((w * sig + 3.0 * g3) * sig + 2.0 * g2) * sig + g1
    return f, d


@njit(cache=True, inline="always")
def _illinois(hi, fhi, flo, g0, g1, g2, g3, g4, g5, g6, a_x, t, hh, P, rec):
    """The Illinois iterations of :func:`locate_sensed_poly` on a bracket (0, hi] with g(0) = flo > 0 >= g(hi) = fhi."""
    lo = 0.0
    last = 0
    for _ in range(200):
        if hi - lo <= LOCATE_TOLERANCE:
            break
        s = hi - fhi * (hi - lo) / (fhi - flo)
        if not (lo < s < hi):
            s = 0.5 * (lo + hi)
        f = _poly_at(s, g0, g1, g2, g3, g4, g5, g6)
        if a_x != 0.0:
            f += a_x * sensed_acceleration(t + s * hh, P, rec)
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
def _quadratic_start(hi, g0, g1, fhi):
    """The first root in (0, hi] of the parabola through g(0) = g0 > 0 with slope g1 there and
    g(hi) = fhi <= 0: where :func:`locate_poly`'s Newton search starts (-1 when there is none).

    g on a step is close to such a parabola (θ under a nearly constant θ̈, θ̇ nearly linear), so
    Newton starts orders of magnitude nearer the root than from the secant's point, which lies on
    the far side of a curved g.
    """
    c = (fhi - g0 - g1 * hi) / (hi * hi)
    disc = g1 * g1 - 4.0 * c * g0
    if not disc >= 0.0:
        return -1.0
    den = math.sqrt(disc) - g1
    if not den > 0.0:
        return -1.0
    return 2.0 * g0 / den  # the root nearest 0, in the form without cancellation


@njit(cache=True)
def locate_poly(hi, g0, g1, g2, g3, g4, g5, g6):
    """The sig in (0, hi] where g = g0 + g1·sig + … + g6·sig^6 (positive at 0; :func:`event_poly`: a
    Taylor step's polynomial, or a Dormand–Prince step's quartic with g5 = g6 = 0, whose Horner values
    are then the quartic's own) reaches <= 0; the callers cut ``hi`` so that g crosses once.

    Newton's method kept inside the bracket [lo, hi] with g(lo) > 0 >= g(hi), started at the root of
    the parabola through g(0), g'(0) and g(hi) (:func:`_quadratic_start`): a Newton point outside
    the bracket is replaced by its midpoint, and once Newton's correction falls below a quarter of
    ``LOCATE_TOLERANCE`` the next point is taken half the tolerance across, which closes the
    bracket. Returns hi once hi - lo <= ``LOCATE_TOLERANCE`` (about four evaluations of g and its
    slope on the events of noisy rocking runs, against about thirteen of g by the Illinois method),
    or -1 when g(hi) > 0 (no crossing before ``hi``). The returned point always has g <= 0.
    """
    fhi = _poly_at(hi, g0, g1, g2, g3, g4, g5, g6)
    if fhi > 0.0:
        return -1.0
    if g0 <= 0.0:
        return hi  # degenerate start on the surface: take the step end
    lo = 0.0
    s = _quadratic_start(hi, g0, g1, fhi)
    if not (lo < s < hi):
        s = 0.5 * hi
    for _ in range(200):
        f, d = _poly_and_slope(s, g0, g1, g2, g3, g4, g5, g6)
        if f <= 0.0:
            hi = s
        else:
            lo = s
        if hi - lo <= LOCATE_TOLERANCE:
            break
        step = f / d if d != 0.0 else 2.0
        if abs(step) < 0.25 * LOCATE_TOLERANCE:
            s = hi - 0.5 * LOCATE_TOLERANCE if f <= 0.0 else lo + 0.5 * LOCATE_TOLERANCE
        else:
            s = s - step
        if not (lo < s < hi):
            s = 0.5 * (lo + hi)
    return hi


@njit(cache=True, **NO_REFCOUNT)
def locate_sensed_poly(hi, g0, g1, g2, g3, g4, g5, g6, a_x, t, hh, P, rec):
    """:func:`locate_poly` for g = polynomial + a_x·Ẍg(t + sig·hh) as the controller senses it (the CS02
    switch), by the Illinois method: the sensed Ẍg is piecewise linear, so g has no usable slope at its
    knots."""
    fhi = _poly_at(hi, g0, g1, g2, g3, g4, g5, g6) + a_x * sensed_acceleration(t + hi * hh, P, rec)
    if fhi > 0.0:
        return -1.0
    flo = g0 + a_x * sensed_acceleration(t, P, rec)
    if flo <= 0.0:
        return hi
    return _illinois(hi, fhi, flo, g0, g1, g2, g3, g4, g5, g6, a_x, t, hh, P, rec)


@njit(cache=True, inline=inline_into("scan_exit"))
def exit_value(mode, t, th, side, kap_max_eff, kap_min_eff, h_on, P, rec, vert):
    """> 0 when the block leaves REST (uplift, |Ẍg| > (g + Ÿg)·tanα) or HOLD (either side of the
    CS01 sliding surface, docs/model.md, "CS01 sliding")."""
    xg = ground_acceleration(t, P, rec) if h_on else 0.0
    yg = vertical_acceleration(t, P, vert)
    if mode == MODE_REST:
        return abs(xg) - (P[I_G] + yg) * math.tan(P[I_ALPHA])
    a_max = side * acceleration(th, 0.0, side, kap_max_eff, 0.0, xg, yg, P)
    a_min = side * acceleration(th, 0.0, side, kap_min_eff, 0.0, xg, yg, P)
    return max(a_max, -a_min)  # leave HOLD when s·a_max >= 0 or s·a_min <= 0


@njit(cache=True, **NO_REFCOUNT)
def scan_exit(mode, t0, t1, th, side, kmx, kmn, h_on, P, rec, vert):
    """First t in (t0, t1] where the exit value becomes >= 0 (> 0 for REST), or -1.

    Records and pulses are linear (or constant) between known-time events, so one piece is exact;
    analytic excitations are scanned in pieces of 1/``REST_HOLD_SCAN_DIVISIONS`` of a period.
    """
    kind = int(P[I_KIND])
    if h_on and (kind == ONE_SINE or kind == MODULATED):
        dt = 2.0 * math.pi / P[I_OMEGA] / REST_HOLD_SCAN_DIVISIONS
    else:
        dt = t1 - t0  # piecewise linear (or constant) on (t0, t1]
    ta = t0
    while ta < t1:
        tb = min(t1, ta + dt)
        if t1 - tb < 1e-12 * dt or tb <= ta:  # (tb <= ta: dt below the float spacing of ta, one piece)
            tb = t1
        vb = exit_value(mode, tb, th, side, kmx, kmn, h_on, P, rec, vert)
        hit = vb > 0.0 if mode == MODE_REST else vb >= 0.0
        if hit:
            lo = ta
            hi = tb
            for _ in range(80):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                vm = exit_value(mode, mid, th, side, kmx, kmn, h_on, P, rec, vert)
                if (vm > 0.0) if mode == MODE_REST else (vm >= 0.0):
                    hi = mid
                else:
                    lo = mid
            return hi
        ta = tb
    return -1.0
