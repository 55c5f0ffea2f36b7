"""The outcome of one simulation (shared by both engines)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from rockstudy.core.constants import NOISE_DT

STATUS_OVERTURNED = "overturned"
STATUS_REST = "rest"
STATUS_TIME_LIMIT = "time limit"
STATUS_CANNOT_OVERTURN = "cannot overturn"
"""Ended after the excitation below the overturning energy (outcome runs only, docs/model.md)."""

STATUS_UNDETERMINED = "undetermined"
"""The fast engine reached its cap on located events before the run ended: no outcome (``message`` says why)."""

FRACTURE_ELEMENTS = ("spring_left", "spring_right", "damper_left", "damper_right")


@dataclass
class SimulationResult:
    """What happened to the block.

    Attributes
    ----------
    status : {"overturned", "rest", "time limit", "cannot overturn", "undetermined"}
        How the simulation ended ("undetermined": the fast engine's event cap, no outcome).
    overturned : bool
        True when the overturning criterion was met (or an early stop proved it would be); False when
        undetermined.
    overturn_time : float
        Time of overturning (NaN if not overturned). [s]
    end_time : float
        Time the simulation stopped. [s]
    max_rotation_ratio : float
        max |θ| / α over the simulation. [-]
    impact_times, uplift_times, rest_times : ndarray
        Times of impacts (θ = 0), uplifts from rest, and returns to rest. [s]
    fracture_times : dict
        Element name ("spring_left", ...) -> time it broke. [s]
    history : dict or None
        On request: arrays ``t`` [s], ``theta`` [rad], ``theta_dot`` [rad/s], ``kappa`` [-],
        ``ground_acceleration`` [m/s^2].
    engine : str
        "fast" or "reference".
    message : str
        Why the outcome is undetermined ("" otherwise).
    """

    status: str
    overturned: bool
    overturn_time: float
    end_time: float
    max_rotation_ratio: float
    impact_times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    uplift_times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    rest_times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    fracture_times: dict = field(default_factory=dict)
    history: dict | None = None
    engine: str = ""
    message: str = ""

    @property
    def n_impacts(self) -> int:
        return int(len(self.impact_times))

    @property
    def overturned_with_impact(self) -> bool:
        """Overturned after at least one impact (mode 2 of Zhang & Makris)."""
        return bool(self.overturned and self.n_impacts > 0)

    def to_dataset(self, block=None, anchorage=None, motion=None, ground_dt: float = NOISE_DT) -> xr.Dataset:
        """The history as a labelled Dataset, in the layout of the history netCDF files.

        See :func:`history_dataset`; requires a run with ``record_history=True``.

        Parameters
        ----------
        block : Block, optional
            Adds the paper's normalisations θ/α and θ̇/(p·α).
        anchorage : Anchorage, optional
            Adds ``stiffness_ratio`` κ/κ_max.
        motion : GroundMotion, optional
            With ``block``, adds the ground motion Ẍ_g/(g·tanα) on its own time axis ``t_ground``.
        ground_dt : float, default NOISE_DT
            Time step of ``t_ground``. [s]
        """
        return history_dataset(self, block, anchorage, motion, ground_dt)

    def _outcome_fields(self) -> dict:
        """The fields both summaries open with: engine, status, outcome, end, peak, impact count."""
        return {
            "engine": self.engine,
            "status": self.status,
            "overturned": None if self.status == STATUS_UNDETERMINED else bool(self.overturned),
            "overturn_time_s": float(self.overturn_time) if np.isfinite(self.overturn_time) else None,
            "end_time_s": float(self.end_time),
            "max_rotation_ratio": float(self.max_rotation_ratio),
            "n_impacts": self.n_impacts,
        }

    def compact_summary(self) -> dict:
        """The outcome in a few fields (JSON-friendly): status, the counts of impacts, uplifts,
        returns to rest and broken elements, the first and last impact, the peak rotation and
        the end time; :meth:`summary` has the full event lists."""
        impacts = np.asarray(self.impact_times, dtype=float)
        out = {
            **self._outcome_fields(),
            "first_impact_s": float(impacts[0]) if impacts.size else None,
            "last_impact_s": float(impacts[-1]) if impacts.size else None,
            "n_uplifts": int(len(self.uplift_times)),
            "n_rests": int(len(self.rest_times)),
            "n_fractures": len(self.fracture_times),
        }
        if self.message:
            out["message"] = self.message
        return out

    def summary(self) -> dict:
        """JSON-friendly summary (no history)."""
        out = {
            **self._outcome_fields(),
            "impact_times_s": [float(x) for x in self.impact_times],
            "uplift_times_s": [float(x) for x in self.uplift_times],
            "rest_times_s": [float(x) for x in self.rest_times],
            "fracture_times_s": {k: float(v) for k, v in self.fracture_times.items()},
        }
        if self.message:
            out["message"] = self.message
        return out


def unique_times(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Indices of the first and of the last sample of each run of equal times in ``t``.

    The engines record an instant where the state jumps (an impact reverses θ̇, the control
    switches κ) twice, before and after the jump; ``last`` keeps each instant once with the state
    after the jump, ``first`` points at the state before it.

    Parameters
    ----------
    t : numpy.ndarray
        Recorded times, non-decreasing (equal neighbours mark a jump). [s]

    Returns
    -------
    first, last : numpy.ndarray of int
        Index of the first and of the last sample of each distinct time, in order.
    """
    t = np.asarray(t, dtype=float)
    if len(t) == 0:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    new = np.ones(len(t), dtype=bool)
    new[1:] = t[1:] != t[:-1]
    first = np.flatnonzero(new)
    last = np.append(first[1:] - 1, len(t) - 1)
    return first, last


def history_dataset(result: SimulationResult, block=None, anchorage=None, motion=None,
                    ground_dt: float = NOISE_DT) -> xr.Dataset:
    """A run's history as a Dataset with a strictly increasing time axis ``t`` and the events on their
    own dimensions (``impact``, ``uplift``, ``rest``; the elements' fracture times as attributes).

    ``t`` (seconds since the start of the ground motion) holds every recorded instant once (the
    integrator's steps and the events); where the state jumps the value is the one just after the
    jump (right-continuous: κ is a step function with ``where="post"``). The axis is not named
    ``time``: CF keeps a coordinate of that name for calendar time ("seconds since <epoch>"), which
    xarray decodes into dates, and ``ds.sel(t=2.0, method="nearest")`` is meant to work. The
    impacts (θ = 0) are on their own dimension ``impact`` with the angular velocity just before and
    just after each (their ratio is the restitution of Eq. 15).

    Parameters
    ----------
    result : SimulationResult
        A run with ``record_history=True``.
    block : Block, optional
        Adds the paper's normalisations θ/α, θ̇/(p·α) (``rotation_ratio``, ``velocity_ratio``,
        ``velocity_before_impact_ratio``, ``velocity_after_impact_ratio``).
    anchorage : Anchorage, optional
        Adds ``stiffness_ratio`` κ/κ_max (κ itself when κ_max = 0).
    motion : GroundMotion, optional
        With ``block``, adds the ground motion Ẍ_g/(g·tanα) sampled every ``ground_dt`` on
        ``t_ground`` (``ground_ratio``).
    ground_dt : float, default NOISE_DT
        Time step of ``t_ground``, from 0 to the end of the run. [s]
    """
    if result.history is None:
        raise ValueError("the simulation has no history: run it with record_history=True")
    h = result.history
    first, last = unique_times(h["t"])
    t = h["t"][last]
    one = {"units": "1"}
    impacts = np.asarray(result.impact_times, dtype=float)
    at = np.searchsorted(t, impacts)
    found = (at < len(t)) & (t[np.minimum(at, max(len(t) - 1, 0))] == impacts) if len(t) else np.zeros(0, bool)
    before = np.full(len(impacts), np.nan)
    after = np.full(len(impacts), np.nan)
    before[found] = h["theta_dot"][first[at[found]]]
    after[found] = h["theta_dot"][last[at[found]]]
    data = {"theta": ("t", h["theta"][last], {"units": "rad", "long_name": "rotation theta"}),
            "theta_dot": ("t", h["theta_dot"][last],
                          {"units": "rad/s", "long_name": "angular velocity (just after a jump at an event)"}),
            "kappa": ("t", h["kappa"][last], {**one, "long_name": "dimensionless stiffness 4Kb^2/(mgR)"}),
            "theta_dot_before_impact": ("impact", before, {"units": "rad/s",
                                                           "long_name": "angular velocity just before the impact"}),
            "theta_dot_after_impact": ("impact", after, {"units": "rad/s",
                                                         "long_name": "angular velocity just after the impact"})}
    if "ground_acceleration" in h:
        data["ground_acceleration"] = ("t", h["ground_acceleration"][last], {"units": "m/s^2", "long_name": "X_g"})
    coords = {"t": ("t", t, {"units": "s", "long_name": "time since the start of the ground motion "
                                                       "(integrator steps and events)"}),
              "impact_time": ("impact", impacts, {"units": "s", "long_name": "time of the impact (theta = 0)"}),
              "uplift_time": ("uplift", np.asarray(result.uplift_times, dtype=float),
                              {"units": "s", "long_name": "time the block uplifted from rest"}),
              "rest_time": ("rest", np.asarray(result.rest_times, dtype=float),
                            {"units": "s", "long_name": "time the block came to rest"})}
    if block is not None:
        scale = block.p * block.alpha
        data["rotation_ratio"] = ("t", h["theta"][last] / block.alpha, {**one, "long_name": "theta/alpha"})
        data["velocity_ratio"] = ("t", h["theta_dot"][last] / scale, {**one, "long_name": "theta_dot/(p alpha)"})
        data["velocity_before_impact_ratio"] = ("impact", before / scale,
                                                {**one, "long_name": "theta_dot/(p alpha) just before the impact"})
        data["velocity_after_impact_ratio"] = ("impact", after / scale,
                                               {**one, "long_name": "theta_dot/(p alpha) just after the impact"})
    if anchorage is not None:
        kappa_ref = anchorage.kappa_max if anchorage.kappa_max > 0 else 1.0
        data["stiffness_ratio"] = ("t", h["kappa"][last] / kappa_ref, {**one, "long_name": "K/K_max"})
    if motion is not None and block is not None:
        t_ground = np.arange(0.0, result.end_time + ground_dt, ground_dt)
        data["ground_ratio"] = ("t_ground", motion.horizontal(t_ground) / block.uplift_acceleration,
                                {**one, "long_name": "X_g/(g tan(alpha))"})
        coords["t_ground"] = ("t_ground", t_ground, {"units": "s", "long_name": "time since the start of the "
                                                     "ground motion (uniform step)"})
    summary = result.summary()
    return xr.Dataset(data, coords=coords,
                      attrs={"status": summary["status"], "overturned": int(summary["overturned"]),
                             "overturn_time_s": np.nan if summary["overturn_time_s"] is None
                             else summary["overturn_time_s"],
                             "end_time_s": summary["end_time_s"], "max_rotation_ratio": summary["max_rotation_ratio"],
                             "n_impacts": summary["n_impacts"], "engine": result.engine,
                             **{f"fracture_time_{name}_s": value for name, value in result.fracture_times.items()}})
