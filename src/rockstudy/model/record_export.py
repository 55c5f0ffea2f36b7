"""A record as a file other tools read: one acceleration sample a line (``one-column``, the layout of
OpenSees' ``timeSeries Path -dt DT -filePath FILE -factor F``, SAP2000 and SeismoStruct), a header naming
the units and then time and acceleration a line (``two-column``), or the PEER NGA ``at2`` layout
(:func:`rockstudy.model.records.write_at2`, in g by the format). Text layouts keep the record's own unit
and say which, with the factor that turns the values into m/s²; :mod:`rockstudy.model.records` reads every
layout back.
"""
from __future__ import annotations

FORMATS = ("one-column", "two-column", "at2")
"""The layouts a record is exported in."""
DEFAULT_FORMAT = "one-column"
"""The layout unless another is named."""


def export_text(times, values, fmt: str, unit: str = "g") -> str:
    """The samples as text: one a line (``one-column``) or a header naming the units and then time and sample a
    line (``two-column``).

    Parameters
    ----------
    times : array_like
        Sample times, written by ``two-column``. [s]
    values : array_like
        The samples, in ``unit``.
    fmt : {"one-column", "two-column"}
        The layout.
    unit : str, default "g"
        The samples' unit, named in the two-column header.
    """
    import numpy as np

    values = np.asarray(values, dtype=float)
    if fmt == "one-column":
        return "".join(f"{a:.9e}\n" for a in values)
    if fmt == "two-column":
        return f"time [s], acceleration [{unit}]\n" + "".join(
            f"{t:.6f} {a:.9e}\n" for t, a in zip(np.asarray(times, float), values))
    raise ValueError(f"format: {fmt!r} is not one of {', '.join(FORMATS)}")


def export_record(record, path, fmt: str, title: str = "") -> dict:
    """Write ``record`` to ``path`` in ``fmt`` and return what a reader needs: ``unit`` of the values written,
    ``to_m_per_s2`` (the factor to m/s²) and, for one column, the OpenSees line reading the file in m/s².

    Parameters
    ----------
    record : rockstudy.model.records.Record
        The record (its ``acceleration`` in m/s², its ``unit`` the unit of its source).
    path : str or pathlib.Path
        The file to write (checked by the caller).
    fmt : {"one-column", "two-column", "at2"}
        The layout.
    title : str, default ""
        An AT2 file's first header line.
    """
    from rockstudy.core.io import write_text
    from rockstudy.model.records import unit_factor, write_at2
    if fmt == "at2":
        write_at2(record, path, title=title or record.name)
        unit = "g"  # the AT2 format's unit
    else:
        unit = record.unit
        write_text(export_text(record.times, record.acceleration / unit_factor(unit), fmt, unit), path)
    factor = unit_factor(unit)
    return {"format": fmt, "unit": unit, "to_m_per_s2": factor,
            "opensees": f"timeSeries Path 1 -dt {record.dt!r} -filePath {path} -factor {factor!r}"
                        if fmt == "one-column" else None}
