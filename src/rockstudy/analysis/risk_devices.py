"""Which devices of a design study's device sweep reach a median: the verdicts of risk-targeted design.

A device's fragility fit may have no finite median: no record overturns the block at any stripe (fit status
"no overturning", :data:`rockstudy.analysis.fragility_fit.NEVER_OVERTURNS`: the median lies above the last
stripe, and the device meets every target), or every record overturns it at every stripe ("all overturned",
:data:`~rockstudy.analysis.fragility_fit.ALWAYS_OVERTURNS`: it meets none). The verdicts here read the fit status
where the median is NaN, so that NaN never stands for either.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from rockstudy.analysis.fragility_fit import ALWAYS_OVERTURNS, NEVER_OVERTURNS, median_reaches

if TYPE_CHECKING:
    import xarray as xr


def devices_meeting(devices: xr.Dataset, median_g: float) -> list[dict]:
    """Which devices of a device sweep have a fragility median at or above ``median_g``, one row per
    (strategy, κ_max, ξ), with the fit status that decides where the median is not finite (a device that never
    overturns on the stripes meets every target, one that always overturns none:
    :func:`device_verdicts`).

    Parameters
    ----------
    devices : xarray.Dataset
        A device sweep (:func:`rockstudy.studies.design.gather_devices`): ``fragility_median`` [g] and
        ``fit_status`` over (strategy, kappa_max, damping_ratio).
    median_g : float
        The median a device must reach, e.g. from :func:`rockstudy.analysis.risk.median_for_target`. [g]

    Returns
    -------
    list of dict
        ``strategy``, ``kappa_max``, ``damping_ratio``, ``median_g`` (None where the fit has none),
        ``fit_status`` ("" when the sweep has none) and ``meets``.
    """
    meets = device_verdicts(devices, median_g)
    rows = []
    for s in devices["strategy"].values:
        for k in devices["kappa_max"].values:
            for xi in devices["damping_ratio"].values:
                at = {"strategy": s, "kappa_max": k, "damping_ratio": xi}
                m = float(devices["fragility_median"].sel(**at))
                status = str(devices["fit_status"].sel(**at).values) if "fit_status" in devices else ""
                rows.append({"strategy": str(s), "kappa_max": float(k), "damping_ratio": float(xi),
                             "median_g": m if math.isfinite(m) else None, "fit_status": status,
                             "meets": bool(meets.sel(**at))})
    return rows


def device_verdicts(devices: xr.Dataset, target_g: float) -> xr.DataArray:
    """Whether each device of the sweep reaches the target median, over (strategy, kappa_max, damping_ratio):
    its median at or above ``target_g``, or its fit status "no overturning"; never for "all overturned"
    (:func:`rockstudy.analysis.fragility_fit.median_reaches`). A NaN median with no status says neither: it
    does not reach.

    Parameters
    ----------
    devices : xarray.Dataset
        The device sweep (:func:`rockstudy.studies.design.gather_devices`).
    target_g : float
        The target median PGA. [g]
    """
    import xarray as xr
    medians = devices["fragility_median"]
    status = devices["fit_status"] if "fit_status" in devices else xr.full_like(medians, "", dtype=object)

    def one(m, st):
        st = str(st)
        if st in (NEVER_OVERTURNS, ALWAYS_OVERTURNS) or math.isfinite(m):
            return median_reaches(float(m), st, target_g)
        return False

    return xr.apply_ufunc(np.vectorize(one, otypes=[bool]), medians, status)
