"""The probability of overturning over the noise realisations of the paper's study.

The paper reduces the noisy spectra to their lower envelope, the lowest overturning amplitude
over N realisations (§5, Figs. 5–6). Behind that envelope lies the share of realisations that
overturn the block at each (ω_p/p, a_p/(g·tanα)) point,

    P(ω_p/p, a_p) = (1/N) Σ_k 1[realisation k overturns the block at (ω_p/p, a_p)],   (Eq. P1)

an estimate of the probability of overturning under the noise model, with binomial standard
error √(P(1 − P)/N). The lower envelope is where P first becomes positive on the way up.
"""
from __future__ import annotations

import math
import time

import numpy as np
import xarray as xr

from rockstudy.analysis.spectra import OUTCOME_MEANINGS, AmplitudeGrid, Scenario, spectrum

OVERTURNED_OUTCOMES = tuple(i for i, m in enumerate(OUTCOME_MEANINGS) if m.startswith("overturned"))
"""Outcome codes of :data:`rockstudy.analysis.spectra.OUTCOME_MEANINGS` that count as overturned."""
UNDETERMINED_OUTCOME = OUTCOME_MEANINGS.index("undetermined")


def probability_from_outcomes(ds: xr.Dataset) -> xr.Dataset:
    """P(overturn) at every grid point from a spectrum computed ``with_map=True`` (Eq. P1).

    Parameters
    ----------
    ds : xarray.Dataset
        A spectrum of :func:`rockstudy.analysis.spectra.spectrum` with ``outcome``
        (realisation × frequency_ratio × amplitude_ratio).

    Returns
    -------
    xarray.Dataset
        ``probability`` and ``probability_se`` (frequency_ratio × amplitude_ratio), the
        counts ``n_overturned`` and ``n_undetermined`` (event-cap runs, counted as not
        overturned, as in the threshold scan), ``n_realisations``, and the spectrum's
        ``threshold`` (lower envelope) and ``threshold_mean``; the spectrum's attributes.
    """
    if "outcome" not in ds:
        raise ValueError("the spectrum has no 'outcome' variable: compute it with with_map=True")
    outcome = ds["outcome"]
    n = outcome.sizes["realisation"]
    overturned = outcome.isin(list(OVERTURNED_OUTCOMES)).sum("realisation")
    undetermined = (outcome == UNDETERMINED_OUTCOME).sum("realisation")
    p = overturned / n
    one = {"units": "1"}
    out = xr.Dataset(
        {
            "probability": (p.dims, p.values, {**one, "long_name": "probability of overturning over the noise "
                                               "realisations (share of realisations that overturn, Eq. P1)"}),
            "probability_se": (p.dims, np.sqrt(p.values * (1 - p.values) / n),
                               {**one, "long_name": "binomial standard error sqrt(P (1 - P) / N)"}),
            "n_overturned": (p.dims, overturned.values.astype(np.int32), {**one, "long_name": "realisations that "
                                                                          "overturn the block"}),
            "n_undetermined": (p.dims, undetermined.values.astype(np.int32),
                               {**one, "long_name": "realisations that hit the engine's event cap (counted as not "
                                "overturned; 0 expected)"}),
            "threshold": ds["threshold"],
            "threshold_mean": ds["threshold_mean"],
        },
        coords={"frequency_ratio": ds["frequency_ratio"], "amplitude_ratio": ds["amplitude_ratio"],
                **{k: ds.coords[k] for k in ("strategy", "noise_level", "sampling_time", "delay") if k in ds.coords},
                "n_realisations": ((), n, {"long_name": "number of noise realisations N"})},
        attrs={**ds.attrs, "title": f"Probability of overturning over {n} noise realisations, "
                                    f"{ds.attrs.get('control_strategy', '')}".rstrip(", "),
               "paper_equations": ds.attrs.get("paper_equations", "") + "; probability over realisations (Eq. P1)"},
    )
    return out


def probability_surface(scenario: Scenario, frequency_ratios, realisations, grid: AmplitudeGrid | None = None,
                        progress_chunks: int = 10) -> xr.Dataset:
    """P(overturn) at every (ω_p/p, a_p/(g·tanα)) grid point over noise realisations (Eq. P1).

    Runs :func:`rockstudy.analysis.spectra.spectrum` with ``with_map=True`` (the outcome of every
    realisation at every grid point, and the threshold scan for the lower envelope) and
    reduces it with :func:`probability_from_outcomes`.

    Parameters
    ----------
    scenario : Scenario
        Strategy, noise level (> 0 for a probability other than 0 or 1), seed, ...
    frequency_ratios : array_like
        ω_p/p values. [-]
    realisations : sequence of int
        Noise realisation indices.
    grid : AmplitudeGrid, optional
        Amplitude ratios of the surface (and of the threshold scan); default ``AmplitudeGrid()``.
    progress_chunks : int, default 10
        Number of batches the runs are split into, each logging its progress
        (:func:`~rockstudy.analysis.spectra.spectrum`).

    Returns
    -------
    xarray.Dataset
        See :func:`probability_from_outcomes`; ``compute_time_s`` in the attributes. [s]
    """
    t0 = time.perf_counter()
    grid = AmplitudeGrid() if grid is None else grid
    ds = spectrum(scenario, frequency_ratios, realisations=realisations, grid=grid, with_map=True,
                  progress_chunks=progress_chunks)
    out = probability_from_outcomes(ds)
    out.attrs["compute_time_s"] = time.perf_counter() - t0
    out.attrs["n_simulations_threshold_scan"] = int(ds["n_simulations"].sum())
    return out


def lowest_positive_amplitude(probability: xr.DataArray) -> xr.DataArray:
    """The lowest amplitude ratio of the grid with P > 0 at each frequency ratio (NaN if none). [-]

    On the grid, this is the lower envelope of the overturning spectra rounded up to the grid:
    the threshold scan of every realisation stops at its first overturning grid point.

    Parameters
    ----------
    probability : xarray.DataArray
        P(overturn) over (frequency_ratio, amplitude_ratio), e.g. of :func:`probability_surface`. [-]
    """
    amps = probability["amplitude_ratio"].values
    positive = probability.transpose("frequency_ratio", "amplitude_ratio").values > 0
    first = np.where(positive.any(axis=1), amps[np.argmax(positive, axis=1)], math.nan)
    return xr.DataArray(first, dims=("frequency_ratio",), coords={"frequency_ratio": probability["frequency_ratio"]},
                        attrs={"units": "1", "long_name": "lowest grid amplitude ratio with P(overturn) > 0"})
