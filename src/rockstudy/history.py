"""Time histories of one simulation as a labelled xarray Dataset (Figs. 2, 3 and 5b)."""
from __future__ import annotations

import numpy as np
import xarray as xr

from . import __version__
from .result import SimulationResult


def history_dataset(result: SimulationResult, scenario, frequency_ratio: float, amplitude_ratio: float,
                    realisation: int = 0) -> xr.Dataset:
    """θ, θ̇, κ and Ẍg against time, with the run's summary and every parameter as attributes.

    Parameters
    ----------
    result : SimulationResult
        A run made with ``record_history=True``.
    scenario : rockstudy.spectra.Scenario
        The scenario it was run with.
    frequency_ratio, amplitude_ratio : float
        ω_p/p and a_p/(g·tanα) of the run. [-]
    realisation : int
        Noise realisation index.
    """
    if result.history is None:
        raise ValueError("history_dataset needs a result simulated with record_history=True")
    h = result.history
    block = scenario.block
    t = np.asarray(h["t"])
    # events leave repeated time stamps (before/after an impact); keep them, index by sample
    ds = xr.Dataset(
        data_vars={
            "theta": ("sample", h["theta"], {"units": "rad", "long_name": "block rotation theta"}),
            "theta_dot": ("sample", h["theta_dot"], {"units": "rad/s", "long_name": "angular velocity theta_dot"}),
            "kappa": ("sample", h["kappa"], {"units": "1", "long_name": "dimensionless device stiffness 4 K b^2/(m g R)"}),
            "stiffness": ("sample", np.asarray(h["kappa"]) * block.mass * block.gravity * block.R / (4 * block.b**2),
                          {"units": "N/m", "long_name": "device stiffness K"}),
            "ground_acceleration": ("sample", h["ground_acceleration"],
                                    {"units": "m/s^2", "long_name": "horizontal ground acceleration Xg_ddot"}),
            "impact_time": ("impact", np.asarray(result.impact_times, float), {"units": "s", "long_name": "impact times"}),
        },
        coords={"time": ("sample", t, {"units": "s", "long_name": "time"})},
        attrs={
            "title": f"Time history, {scenario.control.strategy}, omega_p/p = {frequency_ratio:g}, "
                     f"a_p/(g tan alpha) = {amplitude_ratio:g}",
            "rockstudy_version": __version__,
            "paper_equations": "Eqs. 1-17; Figs. 2, 3, 5b",
            "frequency_ratio": float(frequency_ratio), "amplitude_ratio": float(amplitude_ratio),
            "realisation": int(realisation), "status": result.status, "overturned": int(result.overturned),
            "overturn_time_s": float(result.overturn_time), "max_rotation_ratio": result.max_rotation_ratio,
            "engine": result.engine,
            **scenario.to_attrs(),
        },
    )
    return ds
