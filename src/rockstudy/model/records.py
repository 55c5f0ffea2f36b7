"""Recorded ground motions: read PEER NGA ``.AT2`` files and two-column text/CSV files.

A :class:`Record` is a horizontal ground acceleration sampled at a uniform step, in SI units;
:meth:`Record.motion` turns it into the :class:`~rockstudy.model.excitation.GroundMotion` the
integrators consume (linear interpolation between samples, like the noisy records of §5).

Every record file is read and written here (netCDF files in :mod:`rockstudy.core.io`); a malformed
file is refused with a :class:`RecordFormatError` naming the file, the line and what was expected.

Formats
-------
PEER NGA ``.AT2`` [1]_: three free header lines (database, event and station, "ACCELERATION
TIME SERIES IN UNITS OF G"), a fourth line ``NPTS=  3930, DT=   .0100 SEC`` (the older
``3930   .0100   NPTS, DT`` is accepted too), then the NPTS accelerations in g, any number
per line.

Two-column text or CSV: time [s] and acceleration, separated by commas, semicolons, tabs or
blanks; blank lines and lines starting with ``#`` are skipped; one header line (the first
line that is not a comment) may name the columns, e.g. ``time [s], acceleration [g]``, and
its bracketed unit is used when no unit is given; with a unit for each column, the first is the time
unit (s, ms or min). Times may start anywhere (the first sample is the record's origin), one step apart.

One column with a given step ``dt`` (the file OpenSees reads with ``timeSeries Path -dt``): the
accelerations at t = 0, dt, 2·dt, ... in order, any number per line, with the same comment and
header rules as two columns.

References
----------
.. [1] PEER (2010). *PEER Ground Motion Database, technical report and user's manual*,
   Pacific Earthquake Engineering Research Center, Berkeley (the ``.AT2`` format).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rockstudy.core import limits
from rockstudy.core.constants import STANDARD_GRAVITY, STANDARD_GRAVITY_UNITS  # noqa: F401  (re-exported)
from rockstudy.core.io import write_text
from rockstudy.core.quantities import SIZES, check_arguments, declares
from rockstudy.core.validation import MAX_RECORD_BYTES, MAX_RECORD_SAMPLES, InputError, check_input_file
from rockstudy.model.excitation import GroundMotion


def unit_label(units: str) -> str:
    """The short label of a ``units`` attribute for tables and figures: "g" for :data:`STANDARD_GRAVITY_UNITS`.

    Parameters
    ----------
    units : str
        A ``units`` attribute, e.g. ``"m s-2"`` or :data:`STANDARD_GRAVITY_UNITS`.
    """
    return "g" if units == STANDARD_GRAVITY_UNITS else units

UNITS = {"g": STANDARD_GRAVITY, "m/s^2": 1.0, "m/s2": 1.0, "cm/s^2": 0.01, "cm/s2": 0.01, "gal": 0.01,
         "mm/s^2": 0.001, "mm/s2": 0.001}
"""Acceleration units a record file may use, with their value in m/s^2."""

AT2_SUFFIXES = (".at2",)
UNIFORM_STEP_TOLERANCE = 0.05
"""Largest relative deviation of a time step from the median step in a two-column file (the
printed times may be rounded: 0.00333, 0.00334, ... for 1/300 s). [-]"""

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?"
_NUMBER_RE = re.compile(_NUMBER)
_NPTS_DT_NEW = re.compile(rf"NPTS\s*=\s*(\d+)\s*,?\s*DT\s*=\s*({_NUMBER})", re.IGNORECASE)
_NPTS_DT_OLD = re.compile(rf"^\s*(\d+)\s+({_NUMBER})\s+NPTS\s*,?\s*DT", re.IGNORECASE)
_UNIT_IN_HEADER = re.compile(r"[\[(]\s*([A-Za-z/0-9^*]+)\s*[\])]")
_SEPARATORS = re.compile(r"[,;\s]+")


class RecordFormatError(ValueError):
    """A record file that does not follow its format; the message names the file and line."""

    def __init__(self, path, line: int | None, expected: str, found: str | None = None):
        where = f"{path}" if line is None else f"{path}, line {line}"
        text = f"{where}: expected {expected}"
        if found is not None:
            shown = found if len(found) <= 80 else f"{found[:77]}..."
            text += f", found {shown!r}"
        super().__init__(text)
        self.path, self.line, self.expected, self.found = str(path), line, expected, found


def unit_factor(unit: str) -> float:
    """Value of one ``unit`` of acceleration in m/s^2 (``"g"``, ``"m/s^2"``, ``"cm/s^2"``, ...). [m/s^2]

    Parameters
    ----------
    unit : str
        Unit name, case-insensitive; ``**`` and ``/s/s`` are read as ``^`` and ``/s^2``.

    Raises
    ------
    ValueError
        If ``unit`` is not one of :data:`UNITS`.
    """
    key = str(unit).strip().lower().replace("**", "^").replace("/s/s", "/s^2")
    if key not in UNITS:
        raise ValueError(f"record unit must be one of {', '.join(UNITS)}, got {unit!r}")
    return UNITS[key]


@declares(sizes={"acceleration": MAX_RECORD_SAMPLES}, dt="record_dt")
@dataclass(frozen=True)
class Record:
    """A horizontal ground acceleration sampled at a uniform step.

    Parameters
    ----------
    name : str
        Label of the record (event and station for an ``.AT2`` file).
    dt : float
        Sampling step. [s]
    acceleration : ndarray
        Ground acceleration Ẍ_g at t_i = i·dt, i = 0..n-1, read-only. [m/s^2]
    source : str
        File the record was read from ("" when built in memory).
    unit : str
        Unit of the accelerations in the source file (informative; ``acceleration`` is SI).
    """

    name: str
    dt: float
    acceleration: np.ndarray
    source: str = ""
    unit: str = "m/s^2"

    def __post_init__(self):
        check_arguments("Record", {"dt": self.dt})
        acc = np.array(self.acceleration, dtype=float)
        if acc.ndim != 1 or not 2 <= acc.size <= SIZES["Record", "acceleration"]:
            raise InputError(f"Record.acceleration must be a 1-D array of 2 to {SIZES['Record', 'acceleration']} "
                             f"samples, got shape {acc.shape}")
        if not np.all(np.isfinite(acc)):
            i = int(np.flatnonzero(~np.isfinite(acc))[0])
            raise ValueError(f"record {self.name!r}: the accelerations must be finite; sample {i} (t = {i * self.dt:g} "
                             f"s) is {acc[i]}" + (f" ({self.source})" if self.source else ""))
        acc.setflags(write=False)
        object.__setattr__(self, "acceleration", acc)
        object.__setattr__(self, "dt", float(self.dt))

    @property
    def duration(self) -> float:
        """Time of the last sample, (n − 1)·dt. [s]"""
        return (self.acceleration.size - 1) * self.dt

    @property
    def times(self) -> np.ndarray:
        """Sample times i·dt. [s]"""
        return np.arange(self.acceleration.size) * self.dt

    @property
    def pga(self) -> float:
        """Peak ground acceleration max|Ẍ_g|. [m/s^2]"""
        return float(np.max(np.abs(self.acceleration)))

    @declares(scale="signed_factor")
    def motion(self, scale: float = 1.0) -> GroundMotion:
        """The record as a ground motion ``scale``·Ẍ_g(t), linear between samples, zero after.

        Parameters
        ----------
        scale : float, default 1
            Factor multiplying the record. [-]

        Returns
        -------
        GroundMotion
            ``kind="record"`` with ``amplitude=scale``, ``record`` in m/s^2 and a nominal
            ``omega = 2π/duration`` (not used for records).
        """
        scale = check_arguments("Record.motion", {"scale": scale})["scale"]
        return GroundMotion(kind="record", amplitude=scale, omega=2.0 * math.pi / self.duration,
                            duration=self.duration, record_dt=self.dt, record=self.acceleration)

    def scale_to_pga(self, pga: float) -> float:
        """The factor that gives this record a peak ground acceleration ``pga`` [m/s^2]. [-]

        Parameters
        ----------
        pga : float
            Target peak ground acceleration, finite, >= 0. [m/s^2]
        """
        if not (pga >= 0 and math.isfinite(pga)):
            raise ValueError(f"pga must be a finite number >= 0 [m/s^2], got {pga!r}")
        return pga / self.pga

    def to_attrs(self, prefix: str = "record_") -> dict:
        """Flat attributes for a self-describing dataset.

        Parameters
        ----------
        prefix : str, default ``"record_"``
            Prefix of every attribute name (``record_name``, ``record_dt_s``, ``record_pga_m_s2``, ...).
        """
        return {f"{prefix}name": self.name, f"{prefix}source": self.source, f"{prefix}unit": self.unit,
                f"{prefix}dt_s": self.dt, f"{prefix}npts": int(self.acceleration.size),
                f"{prefix}pga_m_s2": self.pga}


# --- reading ---------------------------------------------------------------------------------------
def _float(token: str) -> float:
    return float(token.replace("D", "E").replace("d", "e"))


def _numbers_of_line(path, number: int, text: str, expected: str) -> list[float]:
    """Every number of a data line; anything else on it is refused."""
    values, pos = [], 0
    for match in _NUMBER_RE.finditer(text):
        gap = text[pos:match.start()]
        if gap.strip(" \t,"):
            raise RecordFormatError(path, number, expected, gap.strip())
        values.append(_float(match.group()))
        pos = match.end()
    rest = text[pos:]
    if rest.strip(" \t,\r\n"):
        raise RecordFormatError(path, number, expected, rest.strip())
    return values


def read_at2(path) -> Record:
    """Read a PEER NGA ``.AT2`` record (accelerations in g) into SI units.

    Parameters
    ----------
    path : str or Path
        The ``.AT2`` file.

    Returns
    -------
    Record
        ``acceleration`` in m/s^2 (g = 9.80665 m/s^2), ``unit="g"``, ``name`` from header line 2.

    Raises
    ------
    RecordFormatError
        Naming the line: fewer than 4 header lines, a units line that is not "UNITS OF G",
        no ``NPTS``/``DT`` on line 4, NPTS < 2 or DT <= 0, a token that is not a number,
        a non-finite value, or more or fewer values than NPTS.
    """
    path = Path(path)
    lines = [text.rstrip("\r\n") for _, text in _lines(path)]
    if len(lines) < 4:
        raise RecordFormatError(path, len(lines) + 1, "4 header lines (title, event, units, 'NPTS= n, DT= dt SEC')",
                                "end of file")
    units = lines[2]
    if not re.search(r"UNITS\s+OF\s+G\b", units, re.IGNORECASE):
        raise RecordFormatError(path, 3, "the units line 'ACCELERATION TIME SERIES IN UNITS OF G'", units.strip())
    match = _NPTS_DT_NEW.search(lines[3]) or _NPTS_DT_OLD.search(lines[3])
    if match is None:
        raise RecordFormatError(path, 4, "'NPTS= <count>, DT= <step> SEC' (or '<count> <step> NPTS, DT')",
                                lines[3].strip())
    npts, dt = int(match.group(1)), _float(match.group(2))
    if not 2 <= npts <= MAX_RECORD_SAMPLES:
        raise RecordFormatError(path, 4, f"2 <= NPTS <= {MAX_RECORD_SAMPLES} (the engine steps to every sample)",
                                str(npts))
    if not (math.isfinite(dt) and dt > 0):
        raise RecordFormatError(path, 4, "DT > 0 [s]", match.group(2))
    values: list[float] = []
    expected = "accelerations in g (numbers only)"
    for number, text in enumerate(lines[4:], start=5):
        if not text.strip():
            continue
        row = _numbers_of_line(path, number, text, expected)
        if any(not math.isfinite(v) for v in row):
            raise RecordFormatError(path, number, "finite accelerations", text.strip())
        if len(values) + len(row) > npts:
            raise RecordFormatError(path, number, f"NPTS = {npts} values in all (line 4)",
                                    f"value {len(values) + len(row)}")
        values.extend(row)
    if len(values) < npts:
        raise RecordFormatError(path, len(lines) + 1, f"NPTS = {npts} values (line 4)",
                                f"end of file after {len(values)} values")
    name = lines[1].strip() or path.stem
    return Record(name=name, dt=dt, acceleration=np.asarray(values) * STANDARD_GRAVITY, source=str(path), unit="g")


MAX_LINE_CHARS = limits.MAX_LINE_CHARS
"""Longest line of a record file (:data:`rockstudy.core.limits.MAX_LINE_CHARS`)."""


def _lines(path):
    """``(line number, text)`` of a text file, read one bounded line at a time (never the whole file, never
    more than :data:`MAX_LINE_CHARS` characters of one line)."""
    with open(path, encoding="utf-8", errors="replace") as fh:
        number = 0
        while True:
            text = fh.readline(MAX_LINE_CHARS + 1)
            if not text:
                return
            number += 1
            if len(text) > MAX_LINE_CHARS:
                raise RecordFormatError(path, number, f"lines of at most {MAX_LINE_CHARS} characters (a few "
                                        "numbers per line)", text[:40])
            yield number, text


def _line_text(path, wanted: int) -> str:
    """The text of line ``wanted`` of a record file (for an error message)."""
    for number, text in _lines(path):
        if number == wanted:
            return text.strip()
    return ""


def _data_lines(path):
    """The lines of a text record that hold data or a header: ``(line number, text, fields)``,
    blank lines and ``#`` comments left out."""
    for number, text in _lines(path):
        stripped = text.strip()
        if stripped and not stripped.startswith("#"):
            yield number, stripped, [f for f in _SEPARATORS.split(stripped) if f]


def _stated_unit(path, unit: str | None, header_unit: str | None, header_example: str) -> str:
    """The acceleration unit: the caller's, else the header's; neither, or both naming different units, is an
    error naming both ways."""
    if unit is not None:
        if header_unit and unit_factor(header_unit) != unit_factor(unit):
            raise RecordFormatError(path, None, f"the unit {unit!r} (unit= / --record-unit) to agree with the header "
                                    f"line's [{header_unit}]; correct one of them")
        return unit
    if not header_unit:
        raise RecordFormatError(path, None, "a stated acceleration unit: pass unit= (--record-unit) or name "
                                f"it in a header line such as '{header_example}'")
    return header_unit


def read_two_column(path, unit: str | None = None) -> Record:
    """Read a two-column text/CSV record: time [s] and acceleration in ``unit``.

    Parameters
    ----------
    path : str or Path
        The file (see the module docstring for the layout).
    unit : str, optional
        Unit of the acceleration column, one of :data:`UNITS`. When None, the header line must
        state it in brackets, e.g. ``time [s], acceleration [cm/s^2]``.

    Returns
    -------
    Record
        ``acceleration`` in m/s^2; ``dt`` the slope of a least-squares line through the times (printed
        times may be rounded); the time origin moved to the first sample.

    Raises
    ------
    RecordFormatError
        Naming the line: a row without exactly two numbers, a non-finite value, a time that
        does not increase, a step more than 5 % off the median step, fewer than 2 rows, or no unit.
    ValueError
        If ``unit`` is not one of :data:`UNITS`.
    """
    from array import array

    path = Path(path)
    header, header_unit, time_factor = None, None, 1.0
    times, values, row_lines = array("d"), array("d"), array("q")
    expected = "two numbers: time [s] and acceleration"
    last = 0
    for number, stripped, fields in _data_lines(path):
        last = number
        try:
            row = [_float(f) for f in fields]
        except ValueError:
            if not times and header is None:  # one header line, before the data
                header, header_unit = number, _header_unit(path, number, stripped, columns=2)
                time_factor = _header_time_factor(path, number, stripped)
                continue
            raise RecordFormatError(path, number, expected, stripped) from None
        if len(row) != 2:
            raise RecordFormatError(path, number, expected, stripped)
        if len(times) >= MAX_RECORD_SAMPLES:
            raise RecordFormatError(path, number, f"at most {MAX_RECORD_SAMPLES} rows (the engine steps to every "
                                    "sample)", stripped)
        if not all(math.isfinite(v) for v in row):
            raise RecordFormatError(path, number, "finite time and acceleration", stripped)
        times.append(row[0])
        values.append(row[1])
        row_lines.append(number)
    if len(times) < 2:
        raise RecordFormatError(path, last + 1, "at least 2 rows of time and acceleration",
                                f"end of file after {len(times)}")
    unit = _stated_unit(path, unit, header_unit, "time [s], acceleration [g]")
    factor = unit_factor(unit)
    t = np.frombuffer(times, dtype=float) * time_factor  # the header's time unit, to seconds
    steps = np.diff(t)
    nonincreasing = np.flatnonzero(steps <= 0)
    if nonincreasing.size:
        i = int(nonincreasing[0]) + 1
        raise RecordFormatError(path, row_lines[i], "a time greater than the previous one",
                                _line_text(path, row_lines[i]))
    typical = float(np.median(steps))
    bad = np.flatnonzero(np.abs(steps - typical) > UNIFORM_STEP_TOLERANCE * typical)
    if bad.size:
        i = int(bad[0]) + 1
        raise RecordFormatError(path, row_lines[i], f"time {t[i - 1] + typical:.6g} s (a uniform step of "
                                f"{typical:.6g} s; resample the record)", _line_text(path, row_lines[i]))
    # the step from a least-squares line through all times: printed times carry rounding
    index = np.arange(len(t))
    dt = float(np.polyfit(index, t, 1)[0])
    return Record(name=path.stem, dt=dt, acceleration=np.frombuffer(values, dtype=float) * factor,
                  source=str(path), unit=unit)


@declares(dt="record_dt")
def read_one_column(path, dt: float, unit: str | None = None) -> Record:
    """Read a one-column record (OpenSees ``timeSeries Path -dt``): accelerations at i·dt.

    Parameters
    ----------
    path : str or Path
        The file: accelerations in order, any number per line; blank lines and ``#`` lines are
        skipped; one header line before the data may state the unit in brackets.
    dt : float
        Time step between samples. [s]
    unit : str, optional
        Acceleration unit, one of :data:`UNITS`; when None, the header line must state it.

    Returns
    -------
    Record
        ``acceleration`` in m/s^2 at t_i = i·dt.

    Raises
    ------
    RecordFormatError
        Naming the line: a token that is not a number, a non-finite value, fewer than 2 values,
        no unit, or a file whose every row holds two numbers with a first column that increases
        by a uniform step (a time column: read it as two columns, without ``dt``).
    ValueError
        If ``dt`` is not a positive finite number or ``unit`` is not one of :data:`UNITS`.
    """
    check_arguments("read_one_column", {"dt": dt})
    from array import array

    path = Path(path)
    header_unit, values = None, array("d")
    widths, firsts = set(), array("d")  # numbers per line, and each line's first number
    seen_header, last = False, 0
    for number, stripped, fields in _data_lines(path):
        last = number
        try:
            row = [_float(f) for f in fields]
        except ValueError:
            if not values and not seen_header:
                seen_header, header_unit = True, _header_unit(path, number, stripped, columns=1)
                continue
            raise RecordFormatError(path, number, "accelerations (numbers only)", stripped) from None
        if not all(math.isfinite(x) for x in row):
            raise RecordFormatError(path, number, "finite accelerations", stripped)
        if len(values) + len(row) > MAX_RECORD_SAMPLES:
            raise RecordFormatError(path, number, f"at most {MAX_RECORD_SAMPLES} accelerations (the engine steps to "
                                    "every sample)", stripped)
        values.extend(row)
        widths.add(len(row))
        firsts.append(row[0])
    if len(values) < 2:
        raise RecordFormatError(path, last + 1, "at least 2 accelerations", f"end of file after {len(values)}")
    if len(firsts) > 2 and widths == {2}:
        raise RecordFormatError(path, None, "one column of accelerations: every row holds two numbers, as a time "
                                "column and an acceleration column do; read it as two columns (without dt / "
                                "--record-dt), or write one acceleration per line")
    if len(firsts) > 2 and len(widths) == 1 and np.all(np.diff(np.frombuffer(firsts, dtype=float)) > 0):
        raise RecordFormatError(path, None, f"one column of accelerations: every row holds {widths.pop()} numbers "
                                "and the first always increases, as a time column does; write one acceleration "
                                "per line")
    unit = _stated_unit(path, unit, header_unit, "acceleration [g]")
    factor = unit_factor(unit)
    return Record(name=path.stem, dt=float(dt), acceleration=np.frombuffer(values, dtype=float) * factor,
                  source=str(path), unit=unit)


TIME_UNITS = {"s": 1.0, "sec": 1.0, "second": 1.0, "seconds": 1.0, "ms": 1e-3, "min": 60.0}
"""Time units a two-column header may give its first column, with their value in seconds."""


def _header_time_factor(path, number: int, text: str) -> float:
    """Seconds per unit of the time column named in a header line: its bracketed unit when the header
    brackets two units (``time [ms], acceleration [g]``); seconds when it brackets one or none."""
    found = _UNIT_IN_HEADER.findall(text)
    if len(found) < 2:
        return 1.0
    unit = found[0].strip().lower()
    if unit not in TIME_UNITS:
        raise RecordFormatError(path, number, f"a time unit among {', '.join(TIME_UNITS)} for the first column",
                                found[0])
    return TIME_UNITS[unit]


def _header_unit(path, number: int, text: str, columns: int) -> str | None:
    """The acceleration unit a header line brackets, if any; refused when it brackets more units than the
    file has ``columns`` (``time [s]; acceleration [m/s^2]; max abs [g]``) or two acceleration units, since the
    file could then be read more than one way."""
    found = _UNIT_IN_HEADER.findall(text)
    if len(found) > columns:
        more = ("; it names a time column too: read it as two columns (without dt / --record-dt)" if columns == 1
                else "")
        raise RecordFormatError(path, number, f"a header naming at most {columns} column unit(s), as the data has "
                                f"{columns} column(s){more}", text)
    known = []
    for candidate in found:
        try:
            unit_factor(candidate)
        except ValueError:
            continue
        known.append(candidate)
    if len({unit_factor(u) for u in known}) > 1:
        raise RecordFormatError(path, number, "one acceleration unit in the header", text)
    return known[-1] if known else None


@declares(dt="column_dt")
def read_record(path, unit: str | None = None, dt: float | None = None, *, names: dict | None = None) -> Record:
    """Read a record file: ``.AT2`` (PEER NGA, in g) by its suffix, one column when ``dt`` is
    given, any other as two columns.

    Parameters
    ----------
    path : str or Path
        The file.
    unit : str, optional
        For text files, the acceleration unit (see :func:`read_two_column`); for an ``.AT2``
        file it must be None or "g" (the format fixes it).
    dt : float, optional
        Time step of a one-column file (:func:`read_one_column`). [s] An ``.AT2`` file states
        its own step and refuses one.
    names : dict, optional
        The caller's name of ``dt`` in error messages (``{"dt": "--record-dt"}``).

    Returns
    -------
    Record

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) if the path is missing, not a regular file (a
        folder, a FIFO, a device) or larger than :data:`~rockstudy.core.validation.MAX_RECORD_BYTES`;
        :class:`RecordFormatError` for a malformed file or more samples than
        :data:`~rockstudy.core.validation.MAX_RECORD_SAMPLES`.
    """
    check_arguments("read_record", {"dt": dt}, names)
    path = check_input_file("record file", path, MAX_RECORD_BYTES)
    if path.suffix.lower() in AT2_SUFFIXES:
        if dt is not None:
            raise ValueError(f"an .AT2 record states its own time step (DT=); dt must be omitted, got {dt!r}")
        if unit not in (None, "g", "G"):
            raise ValueError(f"an .AT2 record is in g by its format; unit must be 'g' or omitted, got {unit!r}")
        return read_at2(path)
    if dt is not None:
        return read_one_column(path, dt, unit)
    return read_two_column(path, unit)


# --- writing ---------------------------------------------------------------------------------------
def at2_text(record: Record, title: str = "rockstudy record (PEER NGA AT2 layout)") -> str:
    """The record in the PEER NGA ``.AT2`` layout, accelerations in g, 5 per line (``%15.7E``).

    Parameters
    ----------
    record : Record
        The record to write.
    title : str, default "rockstudy record (PEER NGA AT2 layout)"
        First header line.
    """
    g = record.acceleration / STANDARD_GRAVITY
    lines = [title, record.name, "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS= {g.size:7d}, DT= {record.dt:.6f} SEC"]
    for i in range(0, g.size, 5):
        lines.append("".join(f"{v:15.7E}" for v in g[i:i + 5]))
    return "\n".join(lines) + "\n"


def write_at2(record: Record, path, title: str = "rockstudy record (PEER NGA AT2 layout)") -> Path:
    """Write ``record`` as a PEER NGA ``.AT2`` file, atomically with the umask's mode
    (:func:`rockstudy.core.io.write_text`). Returns the path.

    Parameters
    ----------
    record : Record
        The record to write.
    path : str or pathlib.Path
        The file to write.
    title : str, default "rockstudy record (PEER NGA AT2 layout)"
        First header line.
    """
    return write_text(at2_text(record, title), path)
