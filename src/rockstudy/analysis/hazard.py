"""Seismic hazard curves of a site: the annual rate of exceedance λ_IM(x) of a peak ground acceleration x.

A hazard curve is given at points (x_i [g], λ_i [1/yr]) with x rising and λ falling. Between points it
is interpolated linearly in (ln x, ln λ) — a power law λ = λ_i (x/x_i)^(−s_i) on each segment, the usual
reading of a hazard curve (Cornell et al. [1]_) — and, below its first and beyond its last point, the
first and last segments' power laws are extended (:data:`EXTENSIONS`). :func:`rockstudy.analysis.risk.annual_rate`
reports how much of a rate of overturning comes from these extensions.

The simplest hazard file is text: two columns, PGA [g] and annual rate of exceedance [1/yr], separated by
a comma or white space; ``#`` starts a comment; blank lines are skipped (:func:`parse_hazard_text`).
:mod:`rockstudy.analysis.hazard_files` reads the files of OpenQuake, nshmp-haz and the USGS hazard tool too,
one or many sites each.

References
----------
.. [1] C. A. Cornell, F. Jalayer, R. O. Hamburger, D. A. Foutch (2002). Probabilistic basis for 2000
   SAC Federal Emergency Management Agency steel moment frame guidelines. Journal of Structural
   Engineering 128(4), 526–533.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

from rockstudy.core import validation

EXTENSIONS = ("loglog", "none")
"""How a hazard curve is read outside its points: ``loglog`` extends the first and last segments' power
laws (below the first and beyond the last point); ``none`` counts nothing outside the curve (a rate of
overturning is then a lower bound)."""

MAX_HAZARD_POINTS = 100_000
"""Most points a hazard curve may have."""
MAX_HAZARD_BYTES = 16 * 2**20
"""Largest hazard file read. [bytes]"""


class HazardFileError(validation.InputError):
    """A hazard file that cannot be read as a hazard curve (the message names the file and the line)."""


@dataclass(frozen=True)
class HazardCurve:
    """Annual rate of exceedance of the peak ground acceleration at a site.

    Parameters
    ----------
    pga_g : array_like
        PGA levels x_i, rising, > 0. [g]
    annual_rate : array_like
        Annual rate of exceedance λ_i at each level, > 0 and not rising (a flat segment: no ground motion
        between its levels). [1/yr]
    source : str
        Where the curve comes from (a file name, a model).
    """

    pga_g: np.ndarray
    annual_rate: np.ndarray
    source: str = field(default="")

    def __post_init__(self):
        x = np.asarray(self.pga_g, dtype=float)
        rate = np.asarray(self.annual_rate, dtype=float)
        if x.ndim != 1 or x.shape != rate.shape or not 2 <= x.size <= MAX_HAZARD_POINTS:
            raise validation.InputError(f"a hazard curve needs 2 to {MAX_HAZARD_POINTS} (PGA, rate) pairs of one "
                                        f"length, got shapes {x.shape} and {rate.shape}")
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(rate)) and np.all(x > 0) and np.all(rate > 0)):
            raise validation.InputError("hazard curve: PGA and annual rate must be finite and > 0")
        if np.any(np.diff(x) <= 0):
            raise validation.InputError("hazard curve: PGA must rise from point to point")
        if np.any(np.diff(rate) > 0):
            raise validation.InputError("hazard curve: the annual rate of exceedance must not rise as PGA rises")
        object.__setattr__(self, "pga_g", x)
        object.__setattr__(self, "annual_rate", rate)

    @property
    def slopes(self) -> np.ndarray:
        """s_i = −d ln λ / d ln x of each segment (≥ 0; 0 on a flat segment). [-]"""
        return -np.diff(np.log(self.annual_rate)) / np.diff(np.log(self.pga_g))

    def rate(self, x) -> np.ndarray:
        """λ_IM(x), log-log interpolated, the end segments' power laws extended outside the points. [1/yr]

        Parameters
        ----------
        x : float or array_like
            PGA, > 0. [g]
        """
        u = np.log(np.asarray(x, dtype=float))
        lu, lr = np.log(self.pga_g), np.log(self.annual_rate)
        i = np.clip(np.searchsorted(lu, u, side="right") - 1, 0, lu.size - 2)
        return np.exp(lr[i] - self.slopes[i] * (u - lu[i]))

    def pga_at_rate(self, annual_rate: float) -> float:
        """The PGA whose rate of exceedance is ``annual_rate`` (the inverse of :meth:`rate`). [g]

        Parameters
        ----------
        annual_rate : float
            Annual rate of exceedance, > 0. [1/yr]
        """
        lr = np.log(self.annual_rate)
        v = math.log(annual_rate)
        i = int(np.clip(np.searchsorted(-lr, -v, side="right") - 1, 0, lr.size - 2))
        if self.slopes[i] == 0:  # a flat segment holds the rate over its whole span: its first point
            return float(self.pga_g[i])
        return float(self.pga_g[i] * math.exp((lr[i] - v) / self.slopes[i]))


def parse_hazard_text(text: str, name: str = "hazard file") -> HazardCurve:
    """A hazard curve from the text of a hazard file (see the module's description).

    Parameters
    ----------
    text : str
        The file's text: lines of PGA [g] and annual rate of exceedance [1/yr].
    name : str, default "hazard file"
        The file's name in error messages, and the curve's ``source``.

    Raises
    ------
    HazardFileError
        Naming ``name`` and the line (1-based) that is not two positive numbers, or whose PGA does not
        rise or whose rate does not fall.
    """
    pga, rate = [], []
    for number, line in enumerate(text.splitlines(), start=1):
        body = line.split("#", 1)[0].strip()
        if not body:
            continue
        cells = [c for c in re.split(r"[,\s]+", body) if c]
        try:
            values = [float(c) for c in cells]
        except ValueError:
            values = []
        if len(values) != 2 or not all(math.isfinite(v) and v > 0 for v in values):
            raise HazardFileError(f"{name}, line {number}: {line.strip()!r} is not two positive numbers "
                                  "(PGA [g], annual rate of exceedance [1/yr]) separated by a comma or spaces")
        if pga and values[0] <= pga[-1]:
            raise HazardFileError(f"{name}, line {number}: PGA {values[0]:g} g does not rise above the previous "
                                  f"line's {pga[-1]:g} g")
        if rate and values[1] > rate[-1]:
            raise HazardFileError(f"{name}, line {number}: the annual rate {values[1]:g} /yr rises above the "
                                  f"previous line's {rate[-1]:g} /yr (rates of exceedance do not rise with PGA)")
        pga.append(values[0])
        rate.append(values[1])
        if len(pga) > MAX_HAZARD_POINTS:
            raise HazardFileError(f"{name}, line {number}: more than {MAX_HAZARD_POINTS} points")
    if len(pga) < 2:
        raise HazardFileError(f"{name}: a hazard curve needs at least 2 points, found {len(pga)}")
    return HazardCurve(np.array(pga), np.array(rate), source=name)


def read_hazard_curve(path, name: str | None = None, unit: str | None = None) -> HazardCurve:
    """The hazard curve of a one-site hazard file, in any layout of
    :func:`rockstudy.analysis.hazard_files.read_hazard_sites` (at most :data:`MAX_HAZARD_BYTES`).

    Parameters
    ----------
    path : str or pathlib.Path
        The hazard file.
    name : str or None, default None
        The input's name in error messages (e.g. a config key); None: the path.
    unit : str or None, default None
        The unit of the PGA levels; None: the file's, else g (checked to be plausible).

    Raises
    ------
    HazardFileError
        Also when the file holds several sites (read them with ``read_hazard_sites``).
    """
    from rockstudy.analysis.hazard_files import read_hazard_sites
    sites = read_hazard_sites(path, name, unit)
    if len(sites) > 1:
        raise HazardFileError(f"{name or path}: {len(sites)} sites; read_hazard_sites gives each one's curve")
    return sites[0].curve
