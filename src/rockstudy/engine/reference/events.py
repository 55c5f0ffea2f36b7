"""Event functions for ``solve_ivp``: the instants at which a smooth piece of motion ends.

As in :func:`scipy.integrate.solve_ivp`, an event is a continuous function g(t, y) whose zero
is located, with a ``direction`` (+1: crossed from below, −1: from above, 0: either) and a
``terminal`` flag (stop the piece there). Each event here is a small object; its ``name``
tells the run which jump to apply (docs/model.md, "The reference engine, part by part").

A piece often starts on the surface of the event just handled (θ = 0 after an impact, θ̇ = 0
after an apex, Ẍg = 0 after a switch). Events are therefore *armed* at the start time t0: there
the value is replaced by a tiny number on the side the crossing comes from, so only a genuine
crossing after t0 is reported.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

ARMED_VALUE = 1e-300
"""Magnitude of an armed event's value at its start time t0. [-]"""


class Event:
    """Base class: a zero of :meth:`value` for ``solve_ivp``, armed at t0.

    Parameters
    ----------
    direction : {1, -1, 0}
        Sign of the slope of g at the zeros that count.
    terminal : bool, default True
        The piece stops at the first such zero.
    t0 : float or None, default None
        Start time of the piece (None: not armed). [s]
    """

    name = "event"

    def __init__(self, direction: int, terminal: bool = True, t0: float | None = None):
        self.direction = direction
        self.terminal = terminal
        self.t0 = t0

    def value(self, t: float, y) -> float:
        """g(t, y), zero on the event surface.

        Parameters
        ----------
        t : float
            Time. [s]
        y : array_like
            State (θ [rad], θ̇ [rad/s]).
        """
        raise NotImplementedError

    def __call__(self, t: float, y) -> float:
        """g(t, y), or a tiny number on the approach side at t0 (armed)."""
        value = self.value(t, y)
        before = -self.direction
        if t == self.t0 and before != 0 and not value * before > 0.0:
            return before * ARMED_VALUE
        return value


class Impact(Event):
    """θ = 0 reached from the working side: Housner's impact, Eq. (14). g = s·θ [rad].

    Parameters
    ----------
    side : {1, -1}
        Pivoting corner.
    t0 : float
        Start of the piece. [s]
    """

    name = "impact"

    def __init__(self, side: int, t0: float):
        super().__init__(-1, True, t0)
        self.side = side

    def value(self, t, y):
        """g(t, y); see the class docstring.

        Parameters
        ----------
        t : float
            Time. [s]
        y : array_like
            State (θ [rad], θ̇ [rad/s]).
        """
        return self.side * y[0]


class Overturn(Event):
    """|θ| reaches the overturning rotation (π/2 or α). g = s·θ − θ_ov [rad].

    Parameters
    ----------
    side : {1, -1}
        Pivoting corner.
    theta_overturn : float
        Overturning rotation θ_ov. [rad]
    t0 : float
        Start of the piece. [s]
    """

    name = "overturn"

    def __init__(self, side: int, theta_overturn: float, t0: float):
        super().__init__(1, True, t0)
        self.side = side
        self.theta_overturn = theta_overturn

    def value(self, t, y):
        """g(t, y); see the class docstring.

        Parameters
        ----------
        t : float
            Time. [s]
        y : array_like
            State (θ [rad], θ̇ [rad/s]).
        """
        return self.side * y[0] - self.theta_overturn


class Fracture(Event):
    """The working spring or damper reaches its ultimate rotation θ_u (Eqs. 8–13). g = s·θ − θ_u [rad].

    Parameters
    ----------
    element : str
        The element's name ("spring_left", ...), also the event's ``name``.
    side : {1, -1}
        Pivoting corner.
    theta_ultimate : float
        Ultimate rotation θ_u. [rad]
    t0 : float
        Start of the piece. [s]
    """

    def __init__(self, element: str, side: int, theta_ultimate: float, t0: float):
        super().__init__(1, True, t0)
        self.name = element
        self.side = side
        self.theta_ultimate = theta_ultimate

    def value(self, t, y):
        """g(t, y); see the class docstring.

        Parameters
        ----------
        t : float
            Time. [s]
        y : array_like
            State (θ [rad], θ̇ [rad/s]).
        """
        return self.side * y[0] - self.theta_ultimate


class Apex(Event):
    """θ̇ = 0 where the CS01 law switches (Eq. 16). g = s·θ̇ [rad/s].

    Parameters
    ----------
    side : {1, -1}
        Pivoting corner.
    vel_sign : {1, -1}
        Sign of s·θ̇ in the piece; ``direction`` is −vel_sign (moving away from upright, s·θ̇
        falls through 0).
    t0 : float
        Start of the piece. [s]
    """

    name = "apex"

    def __init__(self, side: int, vel_sign: int, t0: float):
        super().__init__(-vel_sign, True, t0)
        self.side = side

    def value(self, t, y):
        """g(t, y); see the class docstring.

        Parameters
        ----------
        t : float
            Time. [s]
        y : array_like
            State (θ [rad], θ̇ [rad/s]).
        """
        return self.side * y[1]


class TurningPoint(Event):
    """θ̇ = 0 where no law switches: recorded (not terminal, not armed) to check for missed crossings.

    Parameters
    ----------
    side : {1, -1}
        Pivoting corner. g = s·θ̇ [rad/s]
    """

    name = "turn"

    def __init__(self, side: int):
        super().__init__(0, False, None)
        self.side = side

    def value(self, t, y):
        """g(t, y); see the class docstring.

        Parameters
        ----------
        t : float
            Time. [s]
        y : array_like
            State (θ [rad], θ̇ [rad/s]).
        """
        return self.side * y[1]


class GroundZero(Event):
    """Ẍg = 0 as the controller reads it, where the CS02 law switches (Eq. 17). g = sensed Ẍg(t) [m/s^2].

    Parameters
    ----------
    excitation : Excitation
        Ẍg(t) and its sensed value ``excitation.sensed``. [m/s^2]
    ground_sign : {1, -1}
        Sign of Ẍg in the current half-wave; ``direction`` is −ground_sign.
    t0 : float
        Start of the piece. [s]
    """

    name = "ground"

    def __init__(self, excitation, ground_sign: int, t0: float):
        super().__init__(-ground_sign, True, t0)
        self.excitation = excitation

    def value(self, t, y):
        """g(t, y); see the class docstring.

        Parameters
        ----------
        t : float
            Time. [s]
        y : array_like
            State (θ [rad], θ̇ [rad/s]); not used, the value depends on t only.
        """
        return self.excitation.sensed(t)


class UpliftFromRest(Event):
    """A block at rest is lifted onto one corner: ±Ẍg − (g + Ÿg)·tanα crosses 0 from below (Eq. 15).

    Parameters
    ----------
    dynamics : Dynamics
        Gravity, tanα and the excitation.
    push : {1, -1}
        +1: Ẍg > 0 lifts the block onto θ < 0; −1: Ẍg < 0 lifts it onto θ > 0.
    t0 : float
        Start of the rest piece. [s]
    """

    name = "uplift"

    def __init__(self, dynamics, push: int, t0: float):
        super().__init__(1, True, t0)
        self.dynamics = dynamics
        self.push = push

    def value(self, t, y):
        """g(t, y); see the class docstring.

        Parameters
        ----------
        t : float
            Time. [s]
        y : array_like
            State (θ [rad], θ̇ [rad/s]); not used, the block is at rest.
        """
        d, ex = self.dynamics, self.dynamics.excitation
        return self.push * ex.horizontal(t) - (d.gravity + ex.vertical(t)) * d.tan_alpha


class HoldExit(Event):
    """End of the CS01 sliding mode: s·θ̈ with one stiffness changes sign (docs/model.md item 6).

    With κ_max (``direction`` +1) s·θ̈ rising through 0 means the block leaves outward; with
    κ_min (``direction`` −1) s·θ̈ falling through 0 means it turns back. g = s·θ̈ [rad/s^2].

    Parameters
    ----------
    dynamics : Dynamics
        Equation of motion.
    side : {1, -1}
        Pivoting corner.
    theta : float
        Held rotation. [rad]
    kappa : float
        κ_max or κ_min. [-]
    spring_ok, damper_ok : bool
        The working side's elements are intact.
    direction : {1, -1}
        See above.
    t0 : float
        Start of the held piece. [s]
    """

    name = "hold exit"

    def __init__(self, dynamics, side, theta, kappa, spring_ok, damper_ok, direction, t0):
        super().__init__(direction, True, t0)
        self.dynamics = dynamics
        self.side, self.theta, self.kappa = side, theta, kappa
        self.spring_ok, self.damper_ok = spring_ok, damper_ok

    def value(self, t, y):
        """g(t, y); see the class docstring.

        Parameters
        ----------
        t : float
            Time. [s]
        y : array_like
            State (θ [rad], θ̇ [rad/s]); not used, the held θ is fixed.
        """
        return self.side * self.dynamics.acceleration(t, self.theta, 0.0, self.side, self.kappa, self.spring_ok,
                                                      self.damper_ok)


def _still(t, y):
    """Right-hand side of the trivial ODE y' = 0 used to locate events of time only."""
    return np.zeros(1)


def locate_in_time(t0: float, t1: float, events: list, max_step: float):
    """First crossing in (t0, t1] of events that depend on time only, located by ``solve_ivp``.

    The trivial ODE y' = 0 is integrated with the events as terminal events and a step no
    longer than ``max_step`` (pieces end at record knots, where the functions are linear).

    Parameters
    ----------
    t0, t1 : float
        Interval. [s]
    events : list of Event
        Terminal events whose value depends on t only.
    max_step : float
        Largest step. [s]

    Returns
    -------
    (float, int) or None
        Time of the first crossing and the index of its event, or None.
    """
    sol = solve_ivp(_still, (t0, t1), np.zeros(1), method="RK23", events=events, max_step=max_step,
                    rtol=1e-3, atol=1.0)
    if sol.status == 1:
        for i, te in enumerate(sol.t_events):
            if len(te):
                return float(te[-1]), i
    return None


def fired_event(sol, events: list):
    """The terminal event that stopped a ``solve_ivp`` solution at its last time, or None.

    Parameters
    ----------
    sol : OdeResult
        The solution of ``solve_ivp``; only a stop by an event (``status`` 1) is looked at.
    events : list of Event
        The events passed to ``solve_ivp``, in the same order as ``sol.t_events``.
    """
    if sol.status != 1:
        return None
    t_end = sol.t[-1]
    for event, te in zip(events, sol.t_events):
        if event.terminal and len(te) and te[-1] == t_end:
            return event
    return None
