"""What a reference run writes down: the history, the event logs and the peak rotation.

The recorder turns them into the :class:`~rockstudy.engine.simulation_result.SimulationResult` shared with the
fast engine (the role of ``solve_ivp``'s ``OdeSolution`` and ``t_events``).
"""
from __future__ import annotations

import math

import numpy as np

from rockstudy.engine.simulation_result import STATUS_OVERTURNED, SimulationResult
from rockstudy.model.excitation import GroundMotion

HISTORY_STEP = 2e-3
"""Spacing of the regular history samples (events are added on top). [s]"""

HISTORY_FIELDS = ("t", "theta", "theta_dot", "kappa")
"""Recorded columns: time [s], θ [rad], θ̇ [rad/s], dimensionless stiffness κ [-]."""


def history_grid(t0: float, t1: float) -> np.ndarray:
    """Regular history instants k·HISTORY_STEP strictly inside (t0, t1). [s]

    Parameters
    ----------
    t0, t1 : float
        Start and end of the interval, both excluded. [s]
    """
    k0 = math.floor(t0 / HISTORY_STEP) + 1
    k1 = math.ceil(t1 / HISTORY_STEP) - 1
    if k1 < k0:
        return np.zeros(0)
    grid = np.arange(k0, k1 + 1) * HISTORY_STEP
    return grid[(grid > t0) & (grid < t1)]


def _drop_repeats(history: dict) -> dict:
    """The history without exact repeats (a piece end followed by the unchanged start of the next)."""
    t, theta, theta_dot, kappa = (history[name] for name in HISTORY_FIELDS)
    keep = np.ones(len(t), dtype=bool)
    if len(keep) > 1:
        same = ((t[1:] == t[:-1]) & (theta[1:] == theta[:-1]) & (theta_dot[1:] == theta_dot[:-1])
                & (kappa[1:] == kappa[:-1]))
        keep[1:] = ~same
    return {name: values[keep] for name, values in history.items()}


class Recorder:
    """History samples, impact/uplift/rest times and max |θ| of one run.

    Parameters
    ----------
    enabled : bool
        Keep the time history (the event logs and the peak are always kept).
    theta0 : float
        Initial rotation, the first value of max |θ|. [rad]
    """

    def __init__(self, enabled: bool, theta0: float):
        self.enabled = enabled
        self.columns = {name: [] for name in HISTORY_FIELDS}
        self.impact_times: list[float] = []
        self.uplift_times: list[float] = []
        self.rest_times: list[float] = []
        self.max_abs_theta = abs(theta0)

    def sample(self, t, theta, theta_dot, kappa) -> None:
        """Append samples (nothing when the history is not kept); scalars are repeated to the length of ``t``.

        Parameters
        ----------
        t : float or array_like
            Instants of the samples. [s]
        theta : float or array_like
            Rotation θ at each instant. [rad]
        theta_dot : float or array_like
            Angular velocity θ̇ at each instant. [rad/s]
        kappa : float or array_like
            Dimensionless stiffness κ at each instant. [-]
        """
        if not self.enabled:
            return
        t = np.atleast_1d(np.asarray(t, dtype=float))
        self.columns["t"].append(t)
        for name, value in (("theta", theta), ("theta_dot", theta_dot), ("kappa", kappa)):
            self.columns[name].append(np.broadcast_to(np.asarray(value, dtype=float), t.shape).copy())

    def peak(self, theta_abs: float) -> None:
        """Raise max |θ| to ``theta_abs`` if it is larger.

        Parameters
        ----------
        theta_abs : float
            A rotation magnitude |θ| the block reached. [rad]
        """
        self.max_abs_theta = max(self.max_abs_theta, theta_abs)

    def piece_peak(self, sol, t_end: float, theta_end: float) -> None:
        """Raise max |θ| over a ``solve_ivp`` piece cut at ``t_end``, its steps and events included.

        Parameters
        ----------
        sol : OdeResult
            The piece's ``solve_ivp`` solution (steps and events past ``t_end`` are ignored).
        t_end : float
            Where the piece ends. [s]
        theta_end : float
            θ at ``t_end``. [rad]
        """
        keep = sol.t <= t_end
        self.peak(max(float(np.max(np.abs(sol.y[0, keep]))), abs(theta_end)))
        for te, ye in zip(sol.t_events, sol.y_events):
            if len(te) and te[0] <= t_end:
                self.peak(float(np.max(np.abs(ye[te <= t_end, 0]))))

    def history(self, motion: GroundMotion) -> dict | None:
        """The recorded history with Ẍg at its instants, or None when not recorded.

        Parameters
        ----------
        motion : GroundMotion
            The ground motion, evaluated at the history's instants (``ground_acceleration``). [m/s^2]
        """
        if not self.enabled:
            return None
        joined = {name: np.concatenate(v) if v else np.zeros(0) for name, v in self.columns.items()}
        history = _drop_repeats(joined)
        history["ground_acceleration"] = np.asarray(motion.horizontal(history["t"]), dtype=float)
        return history

    def result(self, status: str, overturn_time: float, end_time: float, alpha: float, fracture_times: dict,
               motion: GroundMotion) -> SimulationResult:
        """The run's :class:`SimulationResult` (``engine="reference"``).

        Parameters
        ----------
        status : str
            How the run ended.
        overturn_time, end_time : float
            Overturning instant (ignored unless overturned) and last instant. [s]
        alpha : float
            Slenderness, the unit of the peak rotation ratio. [rad]
        fracture_times : dict
            Element name -> fracture time. [s]
        motion : GroundMotion
            For Ẍg in the history. [m/s^2]
        """
        overturned = status == STATUS_OVERTURNED
        return SimulationResult(
            status=status,
            overturned=overturned,
            overturn_time=overturn_time if overturned else math.nan,
            end_time=end_time,
            max_rotation_ratio=self.max_abs_theta / alpha,
            impact_times=np.asarray(self.impact_times, dtype=float),
            uplift_times=np.asarray(self.uplift_times, dtype=float),
            rest_times=np.asarray(self.rest_times, dtype=float),
            fracture_times=dict(fracture_times),
            history=self.history(motion),
            engine="reference",
        )
