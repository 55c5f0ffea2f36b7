"""Event maps of the fast engine: what happens to the state at an impact, an uplift, an apex of a
CS01 run, a fracture, and the sampled controller's queue of pending decisions (paper §3)."""
from __future__ import annotations

import math

import numpy as np

from rockstudy.core._inline import njit
from rockstudy.core.constants import ENERGY_MARGIN, ROTATION_TOLERANCE
from rockstudy.engine._kernel.dopri import acceleration
from rockstudy.engine._kernel.layout import LEFT
from rockstudy.model.anchorage import damper_left_intact, damper_right_intact, spring_left_intact, spring_right_intact
from rockstudy.model.equation_of_motion import normalised_energy

TURN_OUT, TURN_BACK, HOLD = 1, 0, -1
"""Apex decisions of CS01: leave outward with K_max, turn back with K_min, stay on the sliding surface."""

REBOUND, UPLIFT, REST = 0, 1, 2
"""What follows an impact (Eqs. 14–15)."""


@njit(cache=True)
def sign(x):
    return 1.0 if x > 0 else (-1.0 if x < 0 else 0.0)


@njit(cache=True)
def apex_decision(th, side, kap_max_eff, kap_min_eff, xg, yg, P):
    """CS01 at θ̇ = 0, θ ≠ 0 (docs/model.md, "CS01 sliding"): compare θ̈ under K_max and under K_min.

    s·a_max >= 0: TURN_OUT (K_max); else s·a_min <= 0: TURN_BACK (K_min); else HOLD (Filippov
    sliding, the device holds the block with a stiffness between the two).
    """
    a_max = side * acceleration(th, 0.0, side, kap_max_eff, 0.0, xg, yg, P)
    if a_max >= 0.0:
        return TURN_OUT
    a_min = side * acceleration(th, 0.0, side, kap_min_eff, 0.0, xg, yg, P)
    if a_min <= 0.0:
        return TURN_BACK
    return HOLD


@njit(cache=True)
def uplift_side(xg):
    """Side a block at rest uplifts onto: the ground pushes it the other way (Makris). [-]"""
    return -sign(xg)


@njit(cache=True)
def can_uplift(xg, yg, gravity, alpha):
    """True when |Ẍg| > (g + Ÿg)·tanα: the ground lifts a block at rest (no preload)."""
    return abs(xg) > (gravity + yg) * math.tan(alpha)


@njit(cache=True)
def impact(thd, side, e, v_rest, xg, yg, gravity, alpha):
    """Impact at θ = 0, Eq. (14), then rest or uplift when the rebound is negligible (Eq. 15).

    Returns (what, side, θ̇) with ``what`` one of REBOUND, UPLIFT, REST.
    """
    v_after = e * thd
    if abs(v_after) < v_rest:
        if can_uplift(xg, yg, gravity, alpha):
            return UPLIFT, uplift_side(xg), 0.0
        return REST, side, 0.0
    return REBOUND, -side, v_after


@njit(cache=True)
def fracture(side, th, t, spring, damper, frac, th_ku, th_du):
    """Break the working-side spring / damper that ``th`` has reached (Eqs. 8–11, permanent).

    ``spring``, ``damper`` (intact flags by corner) and ``frac`` (times: spring L, R, damper L, R)
    are updated in place. A rotation within ROTATION_TOLERANCE of θ_u counts as reaching it.
    """
    sidx = LEFT if side > 0 else 1 - LEFT
    if spring[sidx] > 0.0:
        u = th_ku - ROTATION_TOLERANCE
        intact = spring_left_intact(th, u) if side > 0 else spring_right_intact(th, u)
        if intact == 0:
            spring[sidx] = 0.0
            frac[sidx] = t
    if damper[sidx] > 0.0:
        u = th_du - ROTATION_TOLERANCE
        intact = damper_left_intact(th, u) if side > 0 else damper_right_intact(th, u)
        if intact == 0:
            damper[sidx] = 0.0
            frac[2 + sidx] = t


@njit(cache=True)
def cannot_overturn(th, thd, p, alpha, kappa_low):
    """True when a block free of excitation can provably never reach |θ| = α again.

    W = θ̇²/(2p²) + cos(α − |θ|) + 2·κ_lo·sin²(θ/2) does not increase once the excitation is over
    under continuous FS, PASSIVE, CS01 and CS02 control (proof in docs/model.md, "Early stop below
    the overturning energy"), and reaching |θ| = α needs W >= 1.

    Parameters
    ----------
    th, thd : float
        θ [rad] and θ̇ [rad/s].
    p, alpha : float
        Frequency parameter [rad/s] and slenderness [rad].
    kappa_low : float
        Smallest stiffness the device can apply, times the working spring's fracture function. [-]
    """
    return abs(th) <= alpha and normalised_energy(th, thd, p, alpha, kappa_low) < 1.0 - ENERGY_MARGIN


@njit(cache=True)
def cannot_overturn_switching(th, thd, side, p, alpha, e, kappa_high):
    """True when a block free of excitation can provably never reach |θ| = α again, whatever the
    device does: any stiffness history κ(t) in [0, κ_hi] (sampled and delayed on-off control).

    A stale decision can keep κ_hi while the block returns and so give back energy; the bound
    is over half-cycles (proof in docs/model.md, "Early stop under sampled control"). With
    g(θ) = cos(α − θ) − cos α and S(θ) = 2·sin²(θ/2): outward, E = θ̇²/(2p²) + cos(α − |θ|) cannot
    grow, so the peak θ_a has g(θ_a) <= E − cos α; inward, E + κ_hi·S(θ) cannot grow; an impact
    multiplies the kinetic part u = E − cos α by e². So u at the next impact is at most
    u₁ = e²·(E − cos α + κ_hi·S(θ_a)), and if F(u) = e²·(u + κ_hi·S(θ_a(u))) <= u at u* >= u₁, every
    later u stays <= u* (F increases) and every peak stays below θ_a(u*) < α.

    Parameters
    ----------
    th, thd : float
        θ [rad] and θ̇ [rad/s].
    side : {+1.0, -1.0}
        Pivoting side. [-]
    p, alpha : float
        Frequency parameter [rad/s] and slenderness [rad].
    e : float
        Coefficient of restitution of Eq. (14). [-]
    kappa_high : float
        Largest stiffness the device can apply, κ_max (0 for FS). [-]
    """
    if abs(th) > alpha:
        return False
    energy = normalised_energy(th, thd, p, alpha, 0.0)
    cos_a = math.cos(alpha)
    if side * thd > 0.0:  # outward: the peak of this excursion
        if not energy < 1.0 - ENERGY_MARGIN:
            return False
        peak = alpha - math.acos(energy)
    else:  # inward, or at the apex
        peak = abs(th)
    u_star = e * e * (energy - cos_a + 2.0 * kappa_high * math.sin(0.5 * peak) ** 2) + ENERGY_MARGIN
    if not cos_a + u_star < 1.0 - ENERGY_MARGIN:
        return False
    peak_star = alpha - math.acos(cos_a + u_star)
    return e * e * (u_star + 2.0 * kappa_high * math.sin(0.5 * peak_star) ** 2) <= u_star - ENERGY_MARGIN


# ---- the early stop during the excitation: a bound on the input still to come ---------------
DRIVEN_MARGIN = 1e-2
"""Relative margin of the early stop during the excitation: the bound must clear its level by 1 %,
far above the integrator's energy error over the rest of a run. [-]"""

DRIVEN_NONE, DRIVEN_STEADY, DRIVEN_SWITCHING = 0, 1, 2
"""How a run may stop during the excitation: not at all; with V = V₀ + κ_lo·f·S(θ), which the
device never raises (FS, PASSIVE, continuous CS01, and any strategy whose stiffness does not switch);
with V₀ and the device's largest pumping (CS02 and sampled or delayed switching control)."""


@njit(cache=True)
def peak_rotation(v, alpha):
    """θ_a(v): the rotation at which g(θ) = cos(α − θ) − cos α reaches ``v`` (0 <= v <= 1 − cos α). [rad]"""
    return alpha - math.acos(min(1.0, math.cos(alpha) + v))


@njit(cache=True)
def _psi(v, alpha, kappa_high):
    """Ψ(v) = v + κ·S(θ_a(v)): V₀ plus the spring energy (stiffness κ = ``kappa_high``) at the peak V₀ reaches. [-]"""
    return v + 2.0 * kappa_high * math.sin(0.5 * peak_rotation(v, alpha)) ** 2


@njit(cache=True)
def _free_level_holds(v, alpha, e, kappa_high, kappa_low, sampled):
    """True when a block free of excitation with V₀ <= ``v`` (|θ| <= θ_a(v)) provably never reaches
    |θ| = α again: under any stiffness history in [0, κ_hi] (``sampled``, the half-cycle bound of
    :func:`cannot_overturn_switching` at u = e²·(v + κ_hi·S(θ_a(v)))), else under continuous control
    (the bound of :func:`cannot_overturn`: v + κ_lo·S(θ_a(v)) below 1 − cos α). Both with margin."""
    gap = (1.0 - math.cos(alpha)) * (1.0 - DRIVEN_MARGIN)
    if not v <= gap:
        return False
    if not sampled:
        return _psi(v, alpha, kappa_low) <= gap
    u = e * e * _psi(v, alpha, kappa_high)
    if not u <= gap:
        return False
    return e * e * _psi(u, alpha, kappa_high) <= u * (1.0 - DRIVEN_MARGIN)


@njit(cache=True)
def switching_level(alpha, e, kappa_high, kappa_low, sampled):
    """Largest level v̄ of V₀ = θ̇²/(2p²) + cos(α − |θ|) − cos α at the end of the excitation from
    which the block provably never overturns afterwards (:func:`_free_level_holds`, true on [0, v̄]:
    its left sides increase with v), by bisection to a relative 1e-12. [-]"""
    lo, hi = 0.0, 1.0 - math.cos(alpha)
    if _free_level_holds(hi, alpha, e, kappa_high, kappa_low, sampled):
        return hi
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if _free_level_holds(mid, alpha, e, kappa_high, kappa_low, sampled):
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-12 * hi:
            break
    return lo


@njit(cache=True)
def cannot_overturn_driven(th, thd, p, alpha, impulse, kind, kappa_low, level, pump, kappa_high, ratchet, first):
    """True when a block still under excitation provably never reaches |θ| = α, whatever the
    excitation still to come does within its impulse (docs/engine.md, "Early stops").

    With V₀ = θ̇²/(2p²) + g(θ), g(θ) = cos(α − |θ|) − cos α and S(θ) = 2·sin²(θ/2), the input
    changes V₀ at most by |Ẍg/g|·|θ̇| <= |Ẍg/g|·p·√(2V₀), so √V grows at most by
    J = p/√2·∫|Ẍg/g| dt over the rest of the excitation (``impulse``).

    Parameters
    ----------
    th, thd : float
        θ [rad] and θ̇ [rad/s].
    p, alpha : float
        Frequency parameter [rad/s] and slenderness [rad].
    impulse : float
        J, the bound on the input still to come in units of √V. [-]
    kind : int
        DRIVEN_STEADY: V = V₀ + κ_lo·f·S(θ) (``kappa_low`` = κ_lo·f), which the device never raises,
        must stay below (1 − cos α)(1 − margin), ``level``; DRIVEN_SWITCHING: V₀ grows also by the
        device's pumping, ``pump``, and must stay below ``level`` (:func:`switching_level`), or Q, which
        only the input raises, below one of the ``ratchet`` levels.
    kappa_low : float
        κ_lo·f of the working spring. [-]
    level : float
        The level √V must stay below, squared. [-]
    pump : float
        DRIVEN_SWITCHING: the growth of √V₀ the device can cause over the rest of the excitation,
        p/√2·κ_max·sin θ_a(level) times the time left. [-]
    kappa_high : float
        DRIVEN_SWITCHING: κ_max, the largest stiffness the device can apply. [-]
    ratchet, first : ndarray, int
        DRIVEN_SWITCHING: pairs (Q̄, c) of the bound without the time left (:func:`ratchet_levels`),
        from ``ratchet[first]`` on; the run is safe when (√Q + c·J)² < Q̄ for one of them. [-]
    """
    if abs(th) > alpha:
        return False
    v = thd * thd / (2.0 * p * p) + (math.cos(alpha - abs(th)) - math.cos(alpha))
    if kind == DRIVEN_STEADY:
        v += 2.0 * kappa_low * math.sin(0.5 * th) ** 2
        x = math.sqrt(max(v, 0.0)) + impulse
        return x * x < level
    x = math.sqrt(max(v, 0.0)) + impulse + pump
    if x * x < level:
        return True
    # Q: V₀ + κ_hi·S(θ) returning (θ·θ̇ < 0), else Ψ(V₀) (docs/engine.md)
    q = v + 2.0 * kappa_high * math.sin(0.5 * th) ** 2 if th * thd < 0.0 else _psi(v, alpha, kappa_high)
    rq = math.sqrt(max(q, 0.0))
    for i in range(first, first + 2 * RATCHET_FRACTIONS.shape[0], 2):
        x = rq + ratchet[i + 1] * impulse
        if x * x < ratchet[i]:
            return True
    return False


RATCHET_FRACTIONS = np.array([0.25, 0.4, 0.55, 0.7, 0.85, 1.0])
"""The levels Q̄ of :func:`ratchet_levels`, as fractions of the largest one. [-]"""


@njit(cache=True)
def _impact_contracts(q, alpha, e, kappa_high):
    """Ψ(e²·q) <= q·(1 − margin), with q below (1 − cos α)(1 − margin): an impact lowers Q = q. [-]"""
    return q <= (1.0 - math.cos(alpha)) * (1.0 - DRIVEN_MARGIN) and \
        _psi(e * e * q, alpha, kappa_high) <= q * (1.0 - DRIVEN_MARGIN)


@njit(cache=True)
def ratchet_levels(alpha, e, kappa_high, out, first):
    """The levels of the early stop of a switching device without the time left: pairs (Q̄, c) with
    Q̄ a fraction (``RATCHET_FRACTIONS``) of the largest level at which every impact lowers
    Q (:func:`_impact_contracts`, true on [0, Q̄]: Ψ(e²q)/q increases) and c = Ψ'(Ψ⁻¹(Q̄)) =
    1 + κ_hi·sin θ_a/sin(α − θ_a), the most the input can raise √Q per unit of √V₀ it could raise
    (docs/engine.md, "Early stops"), written to ``out`` from index ``first`` on. [-]"""
    lo, hi = 0.0, 1.0 - math.cos(alpha)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if _impact_contracts(mid, alpha, e, kappa_high):
            lo = mid
        else:
            hi = mid
    for i in range(RATCHET_FRACTIONS.shape[0]):
        q = lo * RATCHET_FRACTIONS[i]
        a, b = 0.0, q  # Ψ⁻¹(q) from above: Ψ(v) >= v, increasing
        for _ in range(60):
            mid = 0.5 * (a + b)
            if _psi(mid, alpha, kappa_high) < q:
                a = mid
            else:
                b = mid
        theta = peak_rotation(b, alpha)
        out[first + 2 * i] = q
        out[first + 2 * i + 1] = 1.0 + kappa_high * math.sin(theta) / math.sin(alpha - theta)


# ---- the sampled controller: decisions wait in a ring buffer until they act -------------------
@njit(cache=True)
def queue_new(delay, sampling_time):
    """Empty queue sized for every decision that can be pending at once (Δτ/T_s + a margin)."""
    n = int(delay / sampling_time) + 4 if sampling_time > 0.0 else 1
    return np.zeros(n), np.zeros(n, dtype=np.bool_)


@njit(cache=True)
def queue_push(times, values, head, count, t_act, value):
    """Append a decision acting at ``t_act``; returns the new count."""
    slot = (head + count) % times.shape[0]
    times[slot] = t_act
    values[slot] = value
    return count + 1
