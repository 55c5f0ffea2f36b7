"""What every command prints: strict JSON (RFC 8259), in one style.

Every command that answers in JSON prints it with :func:`print_json`: two-space indentation, keys in the
order the command builds them, non-ASCII text as it is. A number that is not finite (NaN, ±inf) has no JSON
spelling; instead of printing ``NaN`` (which strict readers such as ``jq`` and JavaScript refuse), the
command fails naming the entry, so that no reader gets a result it cannot parse or a number without
meaning. Commands check their results' ranges before this, naming the input that caused them; this is
the last guard.
"""
from __future__ import annotations

import json
import math
import sys

JSON_INDENT = 2
"""Indentation of every command's JSON output (spaces)."""


GRID_DECIMALS = 10
"""Decimals of the amplitude and frequency grids (:mod:`rockstudy.analysis.spectra` builds them rounded so): a
value found on a grid or by bisection between two of its levels is printed to these decimals, e.g. the midpoint
of 1.8 and 1.85 as 1.825, not as its binary neighbour 1.8250000000000002."""


def grid_values(result: dict, keys) -> dict:
    """``result`` with the entries ``keys`` (those present and not None) rounded to :data:`GRID_DECIMALS`, as
    the grid holds them; only what is printed changes, not what was computed.

    Parameters
    ----------
    result : dict
        A command's result.
    keys : iterable of str
        The entries that are levels of an amplitude or frequency grid (or bisection points between them).
    """
    return {key: round(value, GRID_DECIMALS) if key in keys and isinstance(value, float) else value
            for key, value in result.items()}


class NonFiniteOutputError(ValueError):
    """A result holds NaN or an infinity, which strict JSON cannot carry."""


def _first_non_finite(obj, path: str = "") -> tuple[str, float] | None:
    """The path (``sites[2].probability``) and value of the first non-finite float in ``obj``, or None."""
    if isinstance(obj, float):
        return None if math.isfinite(obj) else (path or "(the result)", obj)
    if isinstance(obj, dict):
        items = ((f"{path}.{k}" if path else str(k), v) for k, v in obj.items())
    elif isinstance(obj, (list, tuple)):
        items = ((f"{path}[{i}]", v) for i, v in enumerate(obj))
    else:
        return None
    for p, v in items:
        found = _first_non_finite(v, p)
        if found is not None:
            return found
    return None


def dumps(obj) -> str:
    """``obj`` as strict JSON text in the commands' style.

    Parameters
    ----------
    obj : dict or list
        The result: dicts, lists, str, int, float (finite), bool and None only.

    Raises
    ------
    NonFiniteOutputError
        ``obj`` holds NaN or an infinity; the message names the entry.
    """
    found = _first_non_finite(obj)
    if found is not None:
        path, value = found
        raise NonFiniteOutputError(f"the result's {path} is {value}, not a finite number; nothing was printed")
    return json.dumps(obj, indent=JSON_INDENT, allow_nan=False, ensure_ascii=False)


def print_json(obj, file=None) -> None:
    """Print ``obj`` as strict JSON (:func:`dumps`) to ``file`` (standard output by default).

    Parameters
    ----------
    obj : dict or list
        The result.
    file : file-like, optional
        Where to print; ``sys.stdout`` when None.
    """
    text = dumps(obj)
    print(text, file=sys.stdout if file is None else file)
