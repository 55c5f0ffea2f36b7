"""The outcome of one simulation (shared by both engines)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

STATUS_OVERTURNED = "overturned"
STATUS_REST = "rest"
STATUS_TIME_LIMIT = "time limit"
STATUS_CANNOT_OVERTURN = "cannot overturn"
"""Ended after the excitation below the overturning energy (outcome runs only, docs/model.md)."""

FRACTURE_ELEMENTS = ("spring_left", "spring_right", "damper_left", "damper_right")


@dataclass
class SimulationResult:
    """What happened to the block.

    Attributes
    ----------
    status : {"overturned", "rest", "time limit", "cannot overturn"}
        How the simulation ended.
    overturned : bool
        True when the overturning criterion was met (or an early stop proved it would be).
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

    @property
    def n_impacts(self) -> int:
        return int(len(self.impact_times))

    @property
    def overturned_with_impact(self) -> bool:
        """Overturned after at least one impact (mode 2 of Zhang & Makris)."""
        return bool(self.overturned and self.n_impacts > 0)

    def summary(self) -> dict:
        """JSON-friendly summary (no history)."""
        def _f(x):
            return None if not np.isfinite(x) else float(x)
        return {
            "engine": self.engine,
            "status": self.status,
            "overturned": bool(self.overturned),
            "overturn_time_s": _f(self.overturn_time),
            "end_time_s": float(self.end_time),
            "max_rotation_ratio": float(self.max_rotation_ratio),
            "n_impacts": self.n_impacts,
            "impact_times_s": [float(x) for x in self.impact_times],
            "uplift_times_s": [float(x) for x in self.uplift_times],
            "rest_times_s": [float(x) for x in self.rest_times],
            "fracture_times_s": {k: float(v) for k, v in self.fracture_times.items()},
        }
