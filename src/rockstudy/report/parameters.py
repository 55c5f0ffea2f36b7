"""Workflow parameters as the report shows them: a source fingerprint by what it covers, the attributes a
rule checks by which inputs, and the label a report item is listed by.
"""
from __future__ import annotations

from rockstudy._version import __version__


class SourceFingerprint(tuple):
    """A source fingerprint as a workflow parameter: compared by its hash, shown by what it covers.

    Snakemake reruns a job when the ``repr`` of a parameter changes, and its report lists the
    parameters formatted (``f"{name}={value}"``). So ``repr`` and ``str`` are the plain hash string's
    (results recorded with the bare hash stay valid, and a script that stores the parameter in a
    dataset stores the hash), while formatting says which sources the result depends on instead of 64
    hex digits. A one-element tuple rather than a ``str``: Snakemake formats string parameters with the
    rule's wildcards, which would turn the value back into a plain string.

    Parameters
    ----------
    digest : str
        The fingerprint (:func:`rockstudy.studies.fingerprints.source_fingerprint`).
    covers : str
        What it covers, e.g. ``"core, model, engine, analysis"``.
    """

    covers: str

    def __new__(cls, digest: str, covers: str):
        obj = super().__new__(cls, (str(digest),))
        obj.covers = covers
        return obj

    @property
    def digest(self) -> str:
        """The SHA-256 hex digest."""
        return self[0]

    @property
    def description(self) -> str:
        """What the report shows: the package version and the sources covered."""
        return f"rockstudy {__version__} sources: {self.covers}"

    def __repr__(self) -> str:
        return repr(self[0])

    def __str__(self) -> str:
        return self[0]

    def __format__(self, spec: str) -> str:
        return format(self.description, spec)

    def __reduce__(self):
        return (SourceFingerprint, (self[0], self.covers))


class ExpectedAttributes(dict):
    """The ``expect`` parameter of a rule (each netCDF input's path -> the attributes it must carry)
    as the report shows it: which inputs are checked, not every attribute.

    A ``dict`` in every other way: ``repr`` (what Snakemake compares to decide a rerun) and what a
    script reads are the plain dictionary's, while formatting (``f"{name}={value}"``, how the report
    lists a job's parameters) gives :attr:`description`, a line instead of thousands of characters.
    """

    @property
    def description(self) -> str:
        """The checked inputs by file name (folder and name), at most three of them named."""
        names = ["/".join(str(path).replace("\\", "/").split("/")[-2:]) for path in self]
        shown = ", ".join(names[:3]) + (f" and {len(names) - 3} more" if len(names) > 3 else "")
        return f"attributes of {shown or 'no input'} checked against this job's settings"

    def __format__(self, spec: str) -> str:
        return format(self.description, spec)

    def __reduce__(self):
        return (ExpectedAttributes, (dict(self),))


def labels(result: str, paper: str = "") -> dict:
    """What a report item shows, for Snakemake's ``report(..., labels=...)``: the report then lists its
    items by this text instead of by file name.

    One label only: the report turns a second label with two values, each on half of a category's
    items, into a toggle between them, which would hide one of two different tables.

    Parameters
    ----------
    result : str
        What the item shows (may contain the rule's ``{wildcards}``).
    paper : str
        Where it is in the paper ("Fig. 6", "Table 1"); empty: beyond the paper.
    """
    return {"result": f"{result} ({paper or 'beyond the paper'})"}
