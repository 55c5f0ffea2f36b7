"""Seismic hazard curves of a site: the annual rate of exceedance λ_IM(x) of a peak ground acceleration x.

A hazard curve is given at points (x_i [g], λ_i [1/yr]) with x rising and λ falling. Between points it
is interpolated linearly in (ln x, ln λ) — a power law λ = λ_i (x/x_i)^(−s_i) on each segment, the usual
reading of a hazard curve (Cornell et al. [1]_) — and, below its first and beyond its last point, the
first and last segments' power laws are extended (:data:`EXTENSIONS`). :func:`rockstudy.analysis.risk.annual_rate`
reports how much of a rate of overturning comes from these extensions.

The simplest hazard file is text: two columns, PGA [g] and annual rate of exceedance [1/yr], separated by
a comma or white space; ``#`` starts a comment; blank lines are skipped (:func:`parse_hazard_text`).
:func:`read_hazard_sites` reads the files of OpenQuake, nshmp-haz and the USGS hazard tool too, one or many
sites each; four layouts, told apart by their content (:func:`parse_hazard_sites`):

* **two columns** -- PGA and annual rate of exceedance [1/yr], comma or space separated, ``#`` comments
  (:func:`parse_hazard_text`); one site. A comment may state the PGA unit:
  ``# PGA [g], annual rate of exceedance [1/yr]``.
* **OpenQuake** hazard-curve CSV (``hazard_curve-mean-PGA_<id>.csv``, ``hazard_curve-mean.csv``): a comment
  line giving ``investigation_time`` and ``imt`` (``# mean, investigation_time=1.0, imt="PGA"`` in older engine
  versions, ``#,,,"generated_by=..., investigation_time=50.0, imt='PGA'"`` in newer ones), then a header
  ``[custom_site_id,]lon,lat[,depth],poe-<level>,...`` and one row per site. A probability of exceedance p in
  the investigation time T is the annual rate λ = −ln(1 − p)/T (Poisson occurrences).
* **nshmp-haz** curves CSV (``curves/PGA/total.csv``): a header ``[name,]lon,lat,<level>,...`` and one row per
  site of annual rates; the IM is the name of the file's folder (``PGA``, ``SA0P2``, ...).
* **USGS hazard tool JSON** (the nshmp-haz-ws ``hazard`` service and the Unified Hazard Tool): ``response``,
  a list of ``{"metadata": {"imt": {"value": "PGA"}, "xvals" or "xvalues": [...]}, "data": [...]}`` whose
  ``data`` entries give ``yvals``/``yvalues`` per site (``latitude``, ``longitude``) or per ``component``
  (``Total`` is read).

Levels whose probability of exceedance is 1 (an infinite rate) and levels of rate 0 at the top of a curve are
dropped, and said in the site's ``notes``; a 0 rate below a positive one, a rising rate, a probability outside
[0, 1] is refused naming the file and line. The IM must be PGA where the file states it. Levels are in g
unless the file or the caller states another unit (:data:`rockstudy.core.risk_inputs.HAZARD_UNITS`); a curve
whose unit is not stated and that no PGA hazard curve in g could be
(:data:`rockstudy.core.limits.PLAUSIBLE_PGA_HAZARD`) is refused, asking for the unit.

References
----------
.. [1] C. A. Cornell, F. Jalayer, R. O. Hamburger, D. A. Foutch (2002). Probabilistic basis for 2000
   SAC Federal Emergency Management Agency steel moment frame guidelines. Journal of Structural
   Engineering 128(4), 526–533.
"""
from __future__ import annotations

import dataclasses
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rockstudy.core import validation
from rockstudy.core.risk_inputs import (
    HAZARD_UNIT_ALIASES,
    HAZARD_UNITS,
    MAX_HAZARD_BYTES,
    MAX_HAZARD_POINTS,
    MAX_HAZARD_SITES,
    PLAUSIBLE_PGA_HAZARD,
)

EXTENSIONS = ("loglog", "none")
"""How a hazard curve is read outside its points: ``loglog`` extends the first and last segments' power
laws (below the first and beyond the last point); ``none`` counts nothing outside the curve (a rate of
overturning is then a lower bound)."""


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
    pga: list[float] = []
    rate: list[float] = []
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
    :func:`read_hazard_sites` (at most :data:`MAX_HAZARD_BYTES`).

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
    sites = read_hazard_sites(path, name, unit)
    if len(sites) > 1:
        raise HazardFileError(f"{name or path}: {len(sites)} sites; read_hazard_sites gives each one's curve")
    return sites[0].curve


# --- the files of hazard tools: one or many sites -------------------------------------------------
HAZARD_FORMATS = ("two-column", "openquake", "nshmp-haz", "usgs-json")
"""The hazard file layouts read (see the module's description)."""
_IMT_FOLDER = re.compile(r"^(PGA|PGV|SA\d+P\d+)$", re.IGNORECASE)


@dataclass(frozen=True)
class HazardSite:
    """One site's PGA hazard curve from a hazard file.

    Attributes
    ----------
    curve : HazardCurve
        λ_IM in g and 1/yr.
    lon, lat : float or None
        The site's longitude and latitude where the file gives them. [deg]
    name : str or None
        The site's name or id where the file gives one.
    notes : tuple of str
        What reading did besides copying numbers (a conversion, levels dropped).
    file_format : str
        One of :data:`HAZARD_FORMATS`.
    """

    curve: HazardCurve
    lon: float | None = None
    lat: float | None = None
    name: str | None = None
    notes: tuple[str, ...] = field(default=())
    file_format: str = "two-column"

    @property
    def label(self) -> str:
        """The site's name, else its coordinates, else the curve's source."""
        if self.name:
            return self.name
        if self.lon is not None and self.lat is not None:
            return f"{self.lon:g},{self.lat:g}"
        return self.curve.source


def check_unit(unit: str | None, name: str = "unit") -> str | None:
    """The canonical spelling of a PGA unit (:data:`rockstudy.core.risk_inputs.HAZARD_UNITS`), or None.

    Parameters
    ----------
    unit : str or None
        The unit as given.
    name : str, default "unit"
        The input's name in the error message (``--hazard-unit``).
    """
    if unit is None:
        return None
    key = HAZARD_UNIT_ALIASES.get(str(unit).strip(), str(unit).strip())
    if key not in HAZARD_UNITS:
        raise validation.InputError(f"{name} = {unit!r} is not a PGA unit: one of {', '.join(HAZARD_UNITS)}")
    return key


def _plausibility(levels_g, rates, where: str) -> str | None:
    """Why a curve, read in g, cannot be a PGA hazard curve (None if it can)."""
    limit = PLAUSIBLE_PGA_HAZARD
    if levels_g[-1] > limit["max_level_g"]:
        return f"levels up to {levels_g[-1]:g}, read as g, exceed {limit['max_level_g']:g} g"
    for at, key in ((1.0, "max_rate_above_1g"), (0.05, "max_rate_above_005g")):
        above = rates[levels_g >= at]
        if above.size and above[0] > limit[key]:
            return (f"the rate {above[0]:.3g} /yr of exceeding {levels_g[levels_g >= at][0]:g} (read as g) is above "
                    f"{limit[key]:g} /yr, which no PGA hazard curve has at {at:g} g or more")
    return None


def _site(levels, rates, *, source: str, where: str, unit: str, unit_stated: bool, notes: list, **site) -> HazardSite:
    """A site from its levels (in ``unit``) and annual rates: zero rates at the top dropped, checked."""
    levels, rates = np.asarray(levels, dtype=float), np.asarray(rates, dtype=float)
    if not (np.all(np.isfinite(rates)) and np.all(rates >= 0)):
        raise HazardFileError(f"{source}, {where}: a rate is negative or not finite")
    rising = np.flatnonzero(np.diff(rates) > 0)
    if rising.size:
        i = int(rising[0]) + 1
        raise HazardFileError(f"{source}, {where}: the rate {rates[i]:g} /yr at level {levels[i]:g} rises above "
                              f"{rates[i - 1]:g} /yr at {levels[i - 1]:g} (rates of exceedance do not rise)")
    zero = rates == 0
    if zero.any():
        notes.append(f"{int(zero.sum())} level(s) from {levels[zero][0]:g} up with rate 0 dropped")
        levels, rates = levels[~zero], rates[~zero]
    if levels.size < 2:
        raise HazardFileError(f"{source}, {where}: fewer than 2 levels with a positive rate ({levels.size})")
    levels_g = levels * HAZARD_UNITS[unit]
    if not unit_stated:
        why = _plausibility(levels_g, rates, where)
        if why:
            raise HazardFileError(f"{source}, {where}: {why}; if the levels are in another unit, state it "
                                  f"(one of {', '.join(HAZARD_UNITS)})")
    elif unit != "g":
        notes.append(f"levels converted from {unit} to g")
    try:
        curve = HazardCurve(levels_g, rates, source=source)
    except validation.InputError as exc:
        raise HazardFileError(f"{source}, {where}: {exc}") from None
    return HazardSite(curve=curve, notes=tuple(notes), **site)


def _numbers(cells, name: str, number: int, what: str) -> list[float]:
    try:
        values = [float(c) for c in cells]
    except ValueError:
        raise HazardFileError(f"{name}, line {number}: {what} must be numbers, got {','.join(cells)[:60]!r}") from None
    if not all(math.isfinite(v) for v in values):
        raise HazardFileError(f"{name}, line {number}: {what} must be finite numbers")
    return values


def _check_imt(imt: str | None, name: str, where: str) -> None:
    if imt is not None and imt.strip().upper() != "PGA":
        raise HazardFileError(f"{name}, {where}: the curve is of {imt.strip()}, not PGA (the fragility is in PGA)")


def _csv_rows(lines):
    """(line number, cells) of the non-blank lines."""
    for number, line in enumerate(lines, start=1):
        if line.strip():
            yield number, [c.strip().strip('"') for c in line.split(",")]


def _parse_openquake(lines, name: str, unit: str, unit_stated: bool) -> list[HazardSite]:
    comment = " ".join(line for line in lines if line.lstrip().startswith("#"))
    found = re.search(r"investigation_time\s*=\s*([0-9.eE+-]+)", comment)
    if not found:
        raise HazardFileError(f"{name}, line 1: an OpenQuake hazard curve needs 'investigation_time=' in its comment "
                              "line (the probabilities of exceedance are in that time)")
    years = float(found.group(1))
    if not (math.isfinite(years) and years > 0):
        raise HazardFileError(f"{name}, line 1: investigation_time = {found.group(1)} is not a positive time [yr]")
    imt = re.search(r"imt\s*=\s*['\"]?([A-Za-z0-9().]+)", comment)
    _check_imt(imt.group(1) if imt else None, name, "line 1")
    rows = [(n, c) for n, c in _csv_rows(lines) if not c[0].startswith("#")]
    (head_line, header), body = rows[0], rows[1:]
    poe_cols = [i for i, c in enumerate(header) if c.startswith("poe-")]
    if "lon" not in header or "lat" not in header or not poe_cols:
        raise HazardFileError(f"{name}, line {head_line}: expected the header lon,lat[,depth],poe-<level>,...")
    levels = _numbers([header[i][4:] for i in poe_cols], name, head_line, "the poe-<level> columns' levels")
    ilon, ilat = header.index("lon"), header.index("lat")
    iname = header.index("custom_site_id") if "custom_site_id" in header else None
    sites = []
    for number, cells in body[:MAX_HAZARD_SITES + 1]:
        if len(cells) != len(header):
            raise HazardFileError(f"{name}, line {number}: {len(cells)} values for the header's {len(header)} columns")
        poe = np.array(_numbers([cells[i] for i in poe_cols], name, number, "probabilities of exceedance"))
        if np.any((poe < 0) | (poe > 1)):
            raise HazardFileError(f"{name}, line {number}: a probability of exceedance lies outside [0, 1]")
        notes = [f"probabilities of exceedance in {years:g} yr converted to annual rates, -ln(1 - p)/T"]
        certain = poe == 1
        if certain.any():  # an infinite rate: nothing to integrate against, the levels are dropped and said
            notes.append(f"{int(certain.sum())} level(s) up to {np.asarray(levels)[certain][-1]:g} with probability "
                         "of exceedance 1 (an infinite rate) dropped")
        keep = ~certain
        rates = -np.log1p(-poe[keep]) / years
        lon, lat = _numbers([cells[ilon], cells[ilat]], name, number, "lon and lat")
        sites.append(_site(np.asarray(levels)[keep], rates, source=name, where=f"line {number}", unit=unit,
                           unit_stated=unit_stated, notes=notes, lon=lon, lat=lat,
                           name=cells[iname] if iname is not None else None, file_format="openquake"))
    return sites


def _parse_nshmp(lines, name: str, unit: str, unit_stated: bool, folder: str | None) -> list[HazardSite]:
    if folder is not None and _IMT_FOLDER.match(folder):
        _check_imt(folder, name, f"its folder {folder!r}")
    rows = list(_csv_rows(lines))
    (head_line, header), body = rows[0], rows[1:]
    first = 3 if header[0] == "name" else 2
    if header[first - 2:first] != ["lon", "lat"]:
        raise HazardFileError(f"{name}, line {head_line}: expected the header [name,]lon,lat,<level>,...")
    levels = _numbers(header[first:], name, head_line, "the level columns")
    sites = []
    for number, cells in body[:MAX_HAZARD_SITES + 1]:
        if len(cells) != len(header):
            raise HazardFileError(f"{name}, line {number}: {len(cells)} values for the header's {len(header)} columns")
        rates = _numbers(cells[first:], name, number, "annual rates")
        lon, lat = _numbers(cells[first - 2:first], name, number, "lon and lat")
        sites.append(_site(levels, rates, source=name, where=f"line {number}", unit=unit, unit_stated=unit_stated,
                           notes=[], lon=lon, lat=lat, name=cells[0] if first == 3 else None, file_format="nshmp-haz"))
    return sites


def _parse_usgs_json(text: str, name: str, unit: str | None) -> list[HazardSite]:
    try:
        doc = json.loads(text)
        responses = doc["response"]
        metas = [r["metadata"] for r in responses]
    except (ValueError, KeyError, TypeError):
        raise HazardFileError(f"{name}: not a USGS hazard JSON (a 'response' list of 'metadata' and 'data')") from None
    imts = [str((m.get("imt") or {}).get("value", "?")) for m in metas]
    pga = [r for r, imt in zip(responses, imts) if imt.upper() == "PGA"]
    if not pga:
        raise HazardFileError(f"{name}: no PGA curve (its curves are of {', '.join(imts)}; the fragility is in PGA)")
    if len(pga) > 1:
        editions = [str((r["metadata"].get("edition") or {}).get("value", "?")) for r in pga]
        raise HazardFileError(f"{name}: {len(pga)} PGA curves (editions {', '.join(editions)}); keep one response")
    meta, data = pga[0]["metadata"], pga[0].get("data") or []
    stated = re.search(r"\(([^)]+)\)", str(meta.get("xlabel", "")))
    file_unit = check_unit(stated.group(1), f"{name}: xlabel") if stated else None
    if unit is not None and file_unit is not None and unit != file_unit:
        raise HazardFileError(f"{name}: the stated unit {unit} differs from the file's xlabel unit {file_unit}")
    levels = meta.get("xvalues", meta.get("xvals"))
    components = [d for d in data if "component" in d]
    if components:
        total = [d for d in components if str(d["component"]).lower() == "total"]
        if not total:
            raise HazardFileError(f"{name}: no 'Total' component among {', '.join(str(d['component']) for d in data)}")
        data = total
    sites = []
    for k, entry in enumerate(data[:MAX_HAZARD_SITES + 1]):
        rates = entry.get("yvalues", entry.get("yvals"))
        if not isinstance(levels, list) or not isinstance(rates, list) or len(levels) != len(rates):
            raise HazardFileError(f"{name}: response data {k}: x and y values of one length are needed")
        lon = entry.get("longitude", meta.get("longitude"))
        lat = entry.get("latitude", meta.get("latitude"))
        sites.append(_site(_numbers([str(v) for v in levels], name, 0, "xvalues"),
                           _numbers([str(v) for v in rates], name, 0, "yvalues"), source=name,
                           where=f"response data {k}", unit=unit or file_unit or "g",
                           unit_stated=(unit or file_unit) is not None, notes=[],
                           lon=None if lon is None else float(lon), lat=None if lat is None else float(lat),
                           file_format="usgs-json"))
    return sites


def _two_column_unit(lines, name: str) -> str | None:
    """The PGA unit a two-column file's comment states (``# PGA [g], annual rate [1/yr]``), if any."""
    for number, line in enumerate(lines, start=1):
        if line.lstrip().startswith("#"):
            found = re.search(r"\bPGA\s*\[([^\]]+)\]", line, re.IGNORECASE)
            if found:
                return check_unit(found.group(1), f"{name}, line {number}: the PGA unit")
    return None


def parse_hazard_sites(text: str, name: str = "hazard file", unit: str | None = None,
                       folder: str | None = None) -> list[HazardSite]:
    """Every site's PGA hazard curve in the text of a hazard file (see the module's description).

    Parameters
    ----------
    text : str
        The file's text.
    name : str, default "hazard file"
        The file's name in error messages and the curves' ``source``.
    unit : str or None, default None
        The unit of the PGA levels (:data:`rockstudy.core.risk_inputs.HAZARD_UNITS`); None: the file's, else g,
        checked to be plausible.
    folder : str or None, default None
        The name of the file's folder: an nshmp-haz curves file's IM.

    Raises
    ------
    HazardFileError
        Naming ``name`` and the line or entry.
    """
    unit = check_unit(unit, f"{name}: unit")
    if text.lstrip().startswith("{"):
        sites = _parse_usgs_json(text, name, unit)
    else:
        lines = text.splitlines()
        data = [line for line in lines if line.strip() and not line.lstrip().startswith("#")]
        header = data[0] if data else ""
        if "poe-" in header or "investigation_time" in text[:2000]:
            sites = _parse_openquake(lines, name, unit or "g", unit is not None)
        elif re.match(r"^\s*(name\s*,\s*)?lon\s*,\s*lat\s*,", header):
            sites = _parse_nshmp(lines, name, unit or "g", unit is not None, folder)
        else:
            curve = parse_hazard_text(text, name)
            stated = _two_column_unit(lines, name)
            if unit is not None and stated is not None and unit != stated:
                raise HazardFileError(f"{name}: the stated unit {unit} differs from the file's header unit {stated}")
            unit = unit or stated
            sites = [_site(curve.pga_g, curve.annual_rate, source=name, where="its points", unit=unit or "g",
                           unit_stated=unit is not None, notes=[], file_format="two-column")]
    if not sites:
        raise HazardFileError(f"{name}: no site (a header and no rows)")
    if len(sites) > MAX_HAZARD_SITES:
        raise HazardFileError(f"{name}: more than {MAX_HAZARD_SITES} sites")
    return sites


def read_hazard_sites(path, name: str | None = None, unit: str | None = None) -> list[HazardSite]:
    """Every site's PGA hazard curve in a hazard file (:func:`parse_hazard_sites`; at most
    :data:`rockstudy.analysis.hazard.MAX_HAZARD_BYTES`).

    Parameters
    ----------
    path : str or pathlib.Path
        The hazard file.
    name : str or None, default None
        The input's name in error messages (e.g. a config key); None: the path.
    unit : str or None, default None
        The unit of the PGA levels; None: the file's, else g (checked to be plausible).
    """
    label = name or str(path)
    path = validation.check_input_file(label, path, MAX_HAZARD_BYTES)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise HazardFileError(f"{label}: not a text file (UTF-8)") from None
    sites = parse_hazard_sites(text, label, unit, folder=Path(path).parent.name)
    return [dataclasses.replace(s, curve=dataclasses.replace(s.curve, source=str(path))) for s in sites]
