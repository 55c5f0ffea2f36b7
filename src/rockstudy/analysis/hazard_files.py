"""Hazard files as the tools that compute them write them: one or several sites' PGA hazard curves.

Four layouts are read, told apart by their content (:func:`parse_hazard_sites`):

* **two columns** -- PGA and annual rate of exceedance [1/yr], comma or space separated, ``#`` comments
  (:func:`rockstudy.analysis.hazard.parse_hazard_text`); one site.
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
(:data:`rockstudy.core.risk_inputs.PLAUSIBLE_PGA_HAZARD`) is refused, asking for the unit.
"""
from __future__ import annotations

import dataclasses
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rockstudy.analysis.hazard import MAX_HAZARD_BYTES, HazardCurve, HazardFileError, parse_hazard_text
from rockstudy.core import validation
from rockstudy.core.risk_inputs import (
    HAZARD_UNIT_ALIASES,
    HAZARD_UNITS,
    MAX_HAZARD_SITES,
    PLAUSIBLE_PGA_HAZARD,
)

FORMATS = ("two-column", "openquake", "nshmp-haz", "usgs-json")
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
        One of :data:`FORMATS`.
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
