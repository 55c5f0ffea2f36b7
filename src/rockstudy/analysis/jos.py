"""J_OS of one overturning spectrum against another (paper Eq. 21), with a_max,0 in units of g.

:func:`jos` is the one rule used by the tables, the command line (``rockstudy jos``) and the Python
API (``rockstudy.jos``): both spectra on the same frequencies, and a_max,0 not above either
spectrum's amplitude scan (a NaN threshold then means "safe up to a_max,0"). The arithmetic of
Eqs. 18–22 is :mod:`rockstudy.analysis.utility_index`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rockstudy.analysis.utility_index import DEFAULT_A_MAX0, utility_index, utility_terms
from rockstudy.core import validation
from rockstudy.core.quantities import check_arguments, declares

if TYPE_CHECKING:
    import xarray as xr


def a_max0_ratio(ds: xr.Dataset, a_max0_g: float, name: str = "a_max0") -> float:
    """a_max,0 given in units of g as an amplitude ratio a/(g·tanα), refused (naming ``name``) when it is
    not positive or lies above the amplitude scan's top recorded in ``ds`` (see
    :func:`rockstudy.core.validation.check_a_max0`). [-]

    Parameters
    ----------
    ds : xarray.Dataset
        A spectrum (:func:`rockstudy.analysis.spectra.spectrum`): its ``block_alpha`` and
        ``grid_amplitude_*`` attributes.
    a_max0_g : float
        The protection level a_max,0, > 0. [g]
    name : str, default "a_max0"
        The input's name in error messages.
    """
    top = validation.scan_top(ds.attrs["grid_amplitude_start"], ds.attrs["grid_amplitude_stop"],
                              ds.attrs["grid_amplitude_step"])
    return validation.check_a_max0(name, a_max0_g, float(ds.attrs["block_alpha"]), top,
                          "the spectrum's scan top, grid_amplitude_stop")


@dataclass(frozen=True)
class JosResult:
    """J_OS of a system against a reference (Eq. 21) and what it is made of.

    Attributes
    ----------
    j_os : float
        Utility index, in [−100, 100]; NaN when N* = 0 (no frequency has a threshold below a_max,0 in
        either spectrum: J_OS undefined). [%]
    n_star : int
        N*, the frequencies counted in Eq. 21.
    a_max0_g : float
        The protection level a_max,0. [g]
    a_max0_ratio : float
        a_max,0 as an amplitude ratio a/(g·tanα). [-]
    frequency_ratio : ndarray
        ω_p/p of the spectra. [-]
    terms : ndarray
        Δa_SYS/Δa_REF at each frequency (Eqs. 18, 22), in [−1, 1]; NaN where both thresholds are capped
        at a_max,0 (not counted). [-]
    """

    j_os: float
    n_star: int
    a_max0_g: float
    a_max0_ratio: float
    frequency_ratio: np.ndarray
    terms: np.ndarray

    @property
    def defined(self) -> bool:
        """Whether J_OS is defined (N* > 0)."""
        return self.n_star > 0 and not math.isnan(self.j_os)


@declares(a_max0_g="a_max0_g")
def jos(system, reference, a_max0_g: float = DEFAULT_A_MAX0, *,
        a_max0_name: str = "a_max0_g") -> JosResult:
    """Utility index J_OS of the spectrum ``system`` against the spectrum ``reference`` (Eq. 21).

    Parameters
    ----------
    system, reference : xarray.Dataset, or callables returning one
        Overturning spectra (:func:`rockstudy.spectrum` or ``rockstudy spectrum``): a ``threshold`` over
        ``frequency_ratio`` and the amplitude scan's attributes. Where no frequency counts (N* = 0) J_OS
        is NaN. Callables (readers of files) are called after ``a_max0_g`` is checked, ``reference`` first.
    a_max0_g : float
        Protection level a_max,0. [g]
    a_max0_name : str
        Name of a_max,0 in error messages (``--a-max0`` on the command line).

    Returns
    -------
    JosResult

    Raises
    ------
    ValueError
        If the spectra are on different frequencies, or a_max,0 is not positive or lies above either
        spectrum's amplitude scan.
    """
    check_arguments("jos", {"a_max0_g": a_max0_g}, {"a_max0_g": a_max0_name})
    if callable(reference):
        reference = reference()
    if callable(system):
        system = system()
    if system.sizes["frequency_ratio"] != reference.sizes["frequency_ratio"] or not np.allclose(
            system["frequency_ratio"], reference["frequency_ratio"]):
        raise ValueError("J_OS needs the system and the reference on the same frequencies")
    ratio = a_max0_ratio(system, a_max0_g, a_max0_name)
    a_max0_ratio(reference, a_max0_g, a_max0_name)
    a_sys, a_ref = system["threshold"].values, reference["threshold"].values
    j, n = utility_index(a_sys, a_ref, ratio, undefined="nan")
    return JosResult(j_os=j, n_star=n, a_max0_g=float(a_max0_g), a_max0_ratio=ratio,
                     frequency_ratio=np.asarray(system["frequency_ratio"].values, dtype=float),
                     terms=utility_terms(a_sys, a_ref, ratio))
