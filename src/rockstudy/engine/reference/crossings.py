"""Event crossings that ``solve_ivp`` stepped over within one step, found and located again.

``solve_ivp`` compares event values only at step ends, so a surface crossed twice within one
step goes unnoticed. Two symptoms reveal it:

* a turning point (θ̇ = 0, itself a recorded event) beyond a threshold: s·θ above an intact
  θ_u or the overturning rotation, or below 0 (a grazing impact);
* a terminal event function that is past its surface at the end of the piece, when another
  event cut the step after the first of the two crossings (e.g. the apex of a small rock
  missed in the step that ends at the next impact).

The step is then integrated again with dense output and the crossing located with
:func:`scipy.optimize.brentq`.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

ROOT_TOLERANCE = 4 * np.finfo(float).eps
"""Absolute and relative tolerance of the root finder on time. [s], [-]"""


class AboveLevel:
    """Gap s·θ − u: positive once the block has passed the rotation u on its side. [rad]"""

    def __init__(self, side: int, level: float):
        self.side, self.level = side, level

    def __call__(self, t, y):
        """The gap at (t, y)."""
        return self.side * y[0] - self.level


class BelowUpright:
    """Gap −s·θ: positive once the block has crossed θ = 0 (a grazing impact). [rad]"""

    def __init__(self, side: int):
        self.side = side

    def __call__(self, t, y):
        """The gap at (t, y)."""
        return -self.side * y[0]


class PastEvent:
    """Gap direction·g(t, y) of an event: positive once its surface has been crossed."""

    def __init__(self, event):
        self.event = event

    def __call__(self, t, y):
        """The gap at (t, y)."""
        return self.event.direction * self.event(t, y)


def _gap_along(t: float, gap, dense) -> float:
    """The gap on the dense output of one step. [rad] or the event's units"""
    return gap(t, dense(t))


def candidates(side: int, turning: list, thresholds: list, watched: list, t_end: float, y_end, atol: float):
    """Gaps that show a missed crossing, each with an upper time bound and its event name.

    Parameters
    ----------
    side : {1, -1}
        Pivoting corner.
    turning : list of (float, ndarray)
        Turning points (θ̇ = 0) of the piece in time order. [s], ([rad], [rad/s])
    thresholds : list of (float, str)
        Rotations s·θ that end the piece when reached from below, with the event name. [rad]
    watched : list of Event
        Terminal events that did not stop the piece.
    t_end, y_end : float, ndarray
        End of the piece and the state there. [s], ([rad], [rad/s])
    atol : float
        Absolute tolerance of the integration: a dip below θ = 0 smaller than this is noise. [rad]

    Returns
    -------
    list of (float, callable, str)
        (upper time bound, gap crossing from < 0 to > 0, event name).
    """
    found = []
    for t_turn, y_turn in turning:
        reached = [(u, name) for u, name in thresholds if side * y_turn[0] >= u]
        if reached:
            level, name = min(reached)
            found.append((t_turn, AboveLevel(side, level), name))
            break
        if side * y_turn[0] < -atol:
            found.append((t_turn, BelowUpright(side), "impact"))
            break
    for event in watched:
        if event.direction * event(t_end, y_end) > 0.0:
            found.append((t_end, PastEvent(event), event.name))
    return found


def missed_crossing(sol, rhs, side: int, turning: list, thresholds: list, watched: list, fired, method: str,
                    rtol: float, atol: float):
    """The earliest event crossing that ``solve_ivp`` stepped over in a piece, if any.

    Parameters
    ----------
    sol : OdeResult
        Solution of the piece.
    rhs : callable
        Its right-hand side.
    side : {1, -1}
        Pivoting corner, as in :func:`candidates`.
    turning : list of (float, ndarray)
        Turning points (θ̇ = 0) of the piece in time order, as in :func:`candidates`. [s], ([rad], [rad/s])
    thresholds : list of (float, str)
        Rotations s·θ that end the piece, with the event name, as in :func:`candidates`. [rad]
    watched : list of Event
        Terminal events that did not stop the piece, as in :func:`candidates`.
    fired : Event or None
        Event that stopped the piece.
    method : str
        Runge–Kutta method for integrating the step again.
    rtol, atol : float
        Tolerances of the integration. [-], [rad] and [rad/s]

    Returns
    -------
    (float, (float, float), str) or None
        (t, (θ, θ̇), name) of the crossing. [s], ([rad], [rad/s])
    """
    t_end = float(sol.t[-1])
    best = None
    steps = {}
    for t_hi, gap, name in candidates(side, turning, thresholds, watched, t_end, sol.y[:, -1], atol):
        j = int(np.searchsorted(sol.t, t_hi, side="left")) - 1
        if j < 0:
            continue
        t_lo = float(sol.t[j])
        if (j, t_hi) not in steps:
            steps[(j, t_hi)] = solve_ivp(rhs, (t_lo, t_hi), sol.y[:, j], method=method, rtol=rtol, atol=atol,
                                         dense_output=True).sol
        dense = steps[(j, t_hi)]
        t_cross = _root(gap, dense, t_lo, t_hi)
        if fired is not None and t_cross >= t_end:
            continue  # simultaneous with the event that stopped the piece: that one wins
        if best is None or t_cross < best[0]:
            y_cross = dense(t_cross)
            best = (t_cross, (float(y_cross[0]), float(y_cross[1])), name)
    return best


def _root(gap, dense, t_lo: float, t_hi: float) -> float:
    """Where the gap crosses 0 in [t_lo, t_hi]; an end if it does not change sign there. [s]"""
    if _gap_along(t_lo, gap, dense) >= 0.0:
        return t_lo
    if _gap_along(t_hi, gap, dense) <= 0.0:  # the excess is below the integration tolerance
        return t_hi
    return brentq(_gap_along, t_lo, t_hi, args=(gap, dense), xtol=ROOT_TOLERANCE, rtol=ROOT_TOLERANCE)
