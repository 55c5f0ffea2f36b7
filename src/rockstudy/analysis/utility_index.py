"""Utility index J_OS of an anchorage/control system against a reference (paper §4, Eqs. 18–22).

Inputs are the lower thresholds of the overturning spectra, a_min,OVER(ω_p/p), of the
investigated system and of the reference, sampled at the same frequencies, and the
acceleration a_max,0 the system must protect against (the paper suggests g).

A NaN threshold means "no overturning found below the scan bound"; it counts as
>= a_max,0, which requires the scan bound to be at least a_max,0 (checked where spectra enter,
by :func:`rockstudy.analysis.jos.jos` and :func:`rockstudy.core.validation.check_a_max0`).

Thresholds and a_max,0 may be given in any one unit (m/s^2, or the amplitude ratios a/(g·tanα)
the spectra store): J_OS is a ratio of differences and does not depend on it.

With a* the thresholds capped at a_max,0 (Eqs. 19–20), each frequency contributes

    Δa_SYS / Δa_REF = (a*_SYS − a*_REF) / (a_max,0 − a*_REF)   if a*_SYS >= a*_REF   (in [0, 1])
                    = (a*_SYS − a*_REF) / a*_REF               if a*_SYS <  a*_REF   (in [−1, 0))

(Eqs. 18, 22), and J_OS = 100 · mean of these over the N* frequencies where either threshold
is below a_max,0 (Eq. 21). Frequencies where both are capped are left out.
"""
from __future__ import annotations

import math

import numpy as np

DEFAULT_A_MAX0 = 1.0
"""The study's protection level a_max,0, in units of g (``a_max0`` of config.yaml, ``--a-max0`` of the CLI)."""


def _check_a_max0(a_max0) -> float:
    if isinstance(a_max0, bool) or not isinstance(a_max0, (int, float, np.integer, np.floating)) or not (
            math.isfinite(a_max0) and a_max0 > 0):
        raise ValueError(f"a_max0 must be a positive finite number (in the thresholds' unit), got {a_max0!r}")
    return float(a_max0)


def _thresholds(name: str, values) -> np.ndarray:
    a = np.asarray(values, dtype=float)
    if np.any(a < 0):  # NaN compares False, so it passes
        raise ValueError(f"{name} must be >= 0 (or NaN for no overturning below the scan bound)")
    return a


def capped_threshold(a_min, a_max0: float):
    """Overturning threshold capped at a_max,0, Eqs. (19)–(20).

    Parameters
    ----------
    a_min : float or array_like
        Minimum overturning acceleration a_min,OVER per frequency; NaN means no overturning
        was found below the scan bound and counts as >= ``a_max0``. [m/s^2]
    a_max0 : float
        Acceleration amplitude the system must be protected against, a_max,0. [m/s^2]

    Returns
    -------
    float or ndarray
        a*_min = a_min where a_min < a_max0, else a_max0 (same shape as ``a_min``). [m/s^2]
    """
    a_max0 = _check_a_max0(a_max0)
    a = _thresholds("a_min", a_min)
    capped = np.where(a < a_max0, a, a_max0)  # NaN < a_max0 is False -> a_max0
    return float(capped) if capped.ndim == 0 else capped


def utility_terms(a_sys, a_ref, a_max0: float) -> np.ndarray:
    """Per-frequency utility ratio Δa_SYS / Δa_REF, Eqs. (18) and (22).

    Parameters
    ----------
    a_sys : array_like
        a_min,OVER of the investigated system per frequency (NaN: none below the scan bound). [m/s^2]
    a_ref : array_like
        a_min,OVER of the reference system, same shape (NaN: none below the scan bound). [m/s^2]
    a_max0 : float
        Protection level a_max,0. [m/s^2]

    Returns
    -------
    ndarray
        Ratio in [−1, 1] per frequency; NaN where both thresholds are capped at a_max0
        (those frequencies do not count in N*, Eq. 21). [-]

    Raises
    ------
    ValueError
        If the shapes differ, a threshold is negative or ``a_max0`` is not positive.
    """
    a_max0 = _check_a_max0(a_max0)
    sys_ = _thresholds("a_sys", a_sys)
    ref = _thresholds("a_ref", a_ref)
    if sys_.shape != ref.shape:
        raise ValueError(f"a_sys and a_ref must have the same shape (one value per frequency), "
                         f"got {sys_.shape} and {ref.shape}")
    sys_star = np.atleast_1d(capped_threshold(sys_, a_max0))
    ref_star = np.atleast_1d(capped_threshold(ref, a_max0))
    counted = (sys_star < a_max0) | (ref_star < a_max0)
    delta_sys = sys_star - ref_star  # Eq. 18
    delta_ref = np.where(sys_star >= ref_star, a_max0 - ref_star, ref_star)  # Eq. 22
    terms = np.full(sys_star.shape, np.nan)
    # Where counted, delta_ref > 0: a*_SYS >= a*_REF needs a*_REF < a_max0, and
    # a*_SYS < a*_REF needs a*_REF > a*_SYS >= 0.
    terms[counted] = delta_sys[counted] / delta_ref[counted]
    return terms.reshape(sys_.shape)


def utility_index(a_sys, a_ref, a_max0: float, undefined: str = "raise") -> tuple[float, int]:
    """Utility index J_OS of a system against a reference, Eq. (21).

    Parameters
    ----------
    a_sys : array_like
        a_min,OVER of the investigated system per frequency (NaN: none below the scan bound). [m/s^2]
    a_ref : array_like
        a_min,OVER of the reference system, same shape. [m/s^2]
    a_max0 : float
        Protection level a_max,0. [m/s^2]
    undefined : {"raise", "nan"}
        What to do when N* = 0: raise a ValueError, or return (NaN, 0).

    Returns
    -------
    j_os : float
        100 × mean of Δa_SYS/Δa_REF over the N* counted frequencies, in [−100, 100]; NaN when
        N* = 0 and ``undefined="nan"``. [%]
    n_star : int
        N*, the number of frequencies where a_min,SYS or a_min,REF is below a_max0.

    Raises
    ------
    ValueError
        If N* = 0 (J_OS undefined) and ``undefined="raise"``, or as :func:`utility_terms`.
    """
    if undefined not in ("raise", "nan"):
        raise ValueError(f"undefined must be 'raise' or 'nan', got {undefined!r}")
    terms = utility_terms(a_sys, a_ref, a_max0)
    counted = ~np.isnan(terms)
    n_star = int(np.count_nonzero(counted))
    if n_star == 0:
        if undefined == "nan":
            return math.nan, 0
        raise ValueError(f"no frequency has a threshold below a_max0 = {a_max0:g} for either system, "
                         "so J_OS (Eq. 21) is undefined (N* = 0)")
    return 100.0 * float(np.mean(terms[counted])), n_star
