"""The check primitives every input check is built from: a finite number, a range, an integer, a non-empty
sequence, and :class:`InputError`, whose message names the input, the value and what is allowed.

Every check takes the name the user typed (``--frequency-step``, ``frequency_grid.step``, ``Block.width``),
the value, and the unit the user gave it in. :mod:`rockstudy.core.validation` gives these under its own name
too, beside the file checks; the relations between inputs and the size of the work are checked in
:mod:`rockstudy.core.relations`.
"""
from __future__ import annotations

import math
import numbers

from rockstudy.core.limits import MAX_INTEGER


class InputError(ValueError):
    """A value the user gave is not allowed; the message names the input, the value and the rule."""


def _fmt(value) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    return repr(value) if isinstance(value, str) else str(value)


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


def field_names(owner: str, names=None):
    """The name of each field of ``owner`` in messages: ``names[field]`` (the caller's option or config key,
    e.g. ``"--kappa-max"`` or ``"anchorage.kappa_max"``), else ``"<owner>.<field>"``.

    Parameters
    ----------
    owner : str
        The class whose fields are named (``"Anchorage"``).
    names : dict, optional
        The caller's name of a field in messages (``{"kappa_max": "--kappa-max"}``); None: every field is
        named ``"<owner>.<field>"``.

    Returns
    -------
    callable
        A function of a field name that returns its name in messages.
    """
    names = names or {}
    return lambda field: names.get(field, f"{owner}.{field}")


def fail(name: str, value, allowed: str, unit: str = ""):
    """Raise :class:`InputError` ``"<name> = <value> <unit> is not allowed: <allowed>"``.

    Parameters
    ----------
    name : str
        The input as the user knows it (``"--kappa-max"``, ``"frequency_grid.step"``).
    value : object
        The value given; a float is written with 6 significant digits, a str quoted.
    allowed : str
        What is allowed, or why the value is refused.
    unit : str, optional
        The unit written after the value ("" for none).

    Raises
    ------
    InputError
        Always.
    """
    raise InputError(f"{name} = {_fmt(value)}{_unit(unit)} is not allowed: {allowed}")


def check_number(name: str, value, unit: str = "") -> float:
    """A finite real number (not a bool, not NaN or inf), returned as a float.

    Parameters
    ----------
    name : str
        The input's name in the message.
    value : object
        The value given.
    unit : str, optional
        The value's unit in the message ("" for none).
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        fail(name, value, "it must be a number")
    value = float(value)
    if not math.isfinite(value):
        fail(name, value, "it must be a finite number (not NaN or inf)", unit)
    return value


def check_range(name: str, value, low: float | None = None, high: float | None = None, unit: str = "", *,
                low_open: bool = False, high_open: bool = False, why: str = "") -> float:
    """A finite number in [low, high], returned as a float.

    Parameters
    ----------
    name : str
        The input's name in the message.
    value : object
        The value given.
    low, high : float or None, optional
        The range's ends; None: unbounded on that side. [unit]
    unit : str, optional
        The unit of the value and the ends, in the message ("" for none).
    low_open, high_open : bool, optional
        Whether the end itself is excluded (default: both included).
    why : str, optional
        Why the range is what it is, appended to the message in parentheses.
    """
    value = check_number(name, value, unit)
    too_low = low is not None and (value <= low if low_open else value < low)
    too_high = high is not None and (value >= high if high_open else value > high)
    if too_low or too_high:
        lo = "" if low is None else f"{_fmt(low)} {'<' if low_open else '<='} "
        hi = "" if high is None else f" {'<' if high_open else '<='} {_fmt(high)}"
        fail(name, value, f"allowed is {lo}{name}{hi}{_unit(unit)}" + (f" ({why})" if why else ""), unit)
    return value


def check_positive(name: str, value, unit: str = "", high: float | None = None, why: str = "") -> float:
    """A finite number > 0 (and <= ``high``), returned as a float.

    Parameters
    ----------
    name : str
        The input's name in the message.
    value : object
        The value given.
    unit : str, optional
        The unit of the value and of ``high``, in the message ("" for none).
    high : float, optional
        The largest value allowed; None: no upper bound. [unit]
    why : str, optional
        Why the limit is what it is, appended to the message in parentheses.
    """
    return check_range(name, value, 0.0, high, unit, low_open=True, why=why)


def check_nonnegative(name: str, value, unit: str = "", high: float | None = None, why: str = "") -> float:
    """A finite number >= 0 (and <= ``high``), returned as a float.

    Parameters
    ----------
    name : str
        The input's name in the message.
    value : object
        The value given.
    unit : str, optional
        The unit of the value and of ``high``, in the message ("" for none).
    high : float, optional
        The largest value allowed; None: no upper bound. [unit]
    why : str, optional
        Why the limit is what it is, appended to the message in parentheses.
    """
    return check_range(name, value, 0.0, high, unit, why=why)


def check_int_range(name: str, value, low: int = 0, high: int = MAX_INTEGER, why: str = "") -> int:
    """An integer (an int, or a float with an integer value) in [low, high], returned as an int.

    Parameters
    ----------
    name : str
        The input's name in the message.
    value : object
        The value given; a bool is refused.
    low, high : int, optional
        The smallest and largest values allowed, both included (default 0 and :data:`MAX_INTEGER`).
    why : str, optional
        Why the range is what it is, appended to the message in parentheses.
    """
    if isinstance(value, bool):
        fail(name, value, "it must be an integer")
    if isinstance(value, numbers.Integral):
        value = int(value)
    elif isinstance(value, numbers.Real) and math.isfinite(value) and float(value).is_integer():
        value = int(float(value))
    else:
        fail(name, value, f"it must be an integer in [{low}, {high}]")
    if not (low <= value <= high):
        fail(name, value, f"allowed is {low} <= {name} <= {high}" + (f" ({why})" if why else ""))
    return value


def check_items(name: str, values, low: int = 1, what: str = "item"):
    """A sequence of at least ``low`` items (a list, a tuple, an array, any iterable): empty data is refused,
    never turned into a number.

    Parameters
    ----------
    name : str
        The argument's name in the message (``"records"``).
    values : iterable
        The items given; a string or a mapping is not a sequence of items.
    low : int, optional
        The fewest items allowed (default 1).
    what : str, optional
        What one item is, in the message (``"record"``).

    Returns
    -------
    sequence
        ``values`` itself when it has a length, else its items as a list.
    """
    if values is None or isinstance(values, (str, bytes, dict)):
        fail(name, values, f"give a sequence of at least {low} {what}(s)")
    try:  # a sized sequence is counted, not copied; an iterator is read into a list
        items = values if hasattr(values, "__len__") else list(values)
        count = len(items)
    except TypeError:
        fail(name, values, f"give a sequence of at least {low} {what}(s)")
    if count < low:
        fail(name, f"{count} {what}(s)", f"give at least {low}")
    return items
