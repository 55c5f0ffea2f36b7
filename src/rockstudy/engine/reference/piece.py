"""One rocking piece: Eq. (1) integrated by ``solve_ivp`` from t0 to its first event.

This is the reference engine's step: :func:`integrate_piece` runs ``solve_ivp`` with the
piece's event objects, reads which terminal event stopped it, and checks for a crossing that
``solve_ivp`` stepped over within one step (:mod:`.crossings`). It does not change the run;
the caller applies the jump.
"""
from __future__ import annotations

from operator import itemgetter

from scipy.integrate import solve_ivp

from rockstudy.engine.reference.crossings import missed_crossing
from rockstudy.engine.reference.events import fired_event

VELOCITY_ZEROS = ("turn", "apex")
"""Names of the events at θ̇ = 0, the turning points of a piece."""


def turning_points(sol, events: list) -> list:
    """Turning points (θ̇ = 0) recorded in a piece, in time order: (t, y). [s], ([rad], [rad/s])

    Parameters
    ----------
    sol : OdeResult
        The ``solve_ivp`` solution of the piece, with ``t_events`` and ``y_events``.
    events : list of Event
        The events passed to ``solve_ivp``, in order; those named in :data:`VELOCITY_ZEROS` are read.
    """
    found = [(float(te), ye) for event, te_all, ye_all in zip(events, sol.t_events, sol.y_events)
             if event.name in VELOCITY_ZEROS for te, ye in zip(te_all, ye_all)]
    return sorted(found, key=itemgetter(0))


def integrate_piece(rhs, events: list, thresholds: list, side: int, span: tuple, y0, method: str, rtol: float,
                    atol: float, dense: bool):
    """Integrate one rocking piece to its first event (or to the end of ``span``).

    Parameters
    ----------
    rhs : RockingRHS
        Right-hand side of Eq. (1) on the piece's corner.
    events : list of Event
        The piece's events (armed at span[0]).
    thresholds : list of (float, str)
        Rotations s·θ that end the piece when reached, with their event names. [rad]
    side : {1, -1}
        Pivoting corner.
    span : (float, float)
        Start and latest end of the piece. [s]
    y0 : ndarray
        (θ, θ̇) at the start. [rad], [rad/s]
    method : str
        ``solve_ivp`` method.
    rtol, atol : float
        Tolerances. [-], [rad] and [rad/s]
    dense : bool
        Keep the dense output (for the history).

    Returns
    -------
    sol : OdeResult
        The ``solve_ivp`` solution (its tail may lie past the end when a crossing was missed).
    end : (float, float, float)
        t [s], θ [rad], θ̇ [rad/s] where the piece ends.
    event : Event or None
        The event that ends it; None at the end of ``span``.

    Raises
    ------
    RuntimeError
        If ``solve_ivp`` fails.
    """
    sol = solve_ivp(rhs, span, y0, method=method, rtol=rtol, atol=atol, events=events, dense_output=dense)
    if sol.status < 0:
        raise RuntimeError(f"solve_ivp failed at t = {span[0]} s: {sol.message}")
    fired = fired_event(sol, events)
    watched = [event for event in events if event.terminal and event is not fired]
    missed = missed_crossing(sol, rhs, side, turning_points(sol, events), thresholds, watched, fired, method,
                             rtol, atol)
    if missed is None:
        return sol, (float(sol.t[-1]), float(sol.y[0, -1]), float(sol.y[1, -1])), fired
    t_end, (theta_end, theta_dot_end), name = missed
    return sol, (t_end, theta_end, theta_dot_end), next(event for event in events if event.name == name)
