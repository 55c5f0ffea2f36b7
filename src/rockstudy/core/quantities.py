"""What every numeric input is, declared once: its unit, its range and whether it is an integer.

A :class:`Quantity` declares one kind of input (a frequency ratio, a block dimension, a seed). Each way a
value enters names the quantity it is, and takes its check from it:

* the library's arguments -- each public class and function declares the quantity of each of its numeric
  arguments where it is defined (:func:`declares`, which fills :data:`ARGUMENTS`), and
  :func:`check_arguments` is the check those classes and functions run first;
* the study config -- :mod:`rockstudy.studies.config_model` builds its pydantic fields from
  :meth:`Quantity.annotated`, so the JSON schema Snakemake validates against carries the same ranges;
* the command line -- an option is checked by the class or function it is passed to, which names the option
  in its message (``names={"kappa_max": "--kappa-max"}``, the argument of :func:`check_arguments`).

The inputs of the risk analyses (fragility median and dispersion, exposure time, earthquake scenarios) are
declared the same way, beside their defaults, in :mod:`rockstudy.core.risk_inputs`.

Relations between inputs (``kappa_min <= kappa_max``, a grid's start below its stop, a run's time span) are
not a single input's range: the functions that take the related inputs check them, after these.

This module imports neither numba, xarray nor pydantic (:meth:`Quantity.annotated` imports pydantic when the
config declarations call it), so the library's checks cost no import.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from rockstudy.core import limits as lim
from rockstudy.core import validation as v
from rockstudy.core.limits import (  # noqa: F401 -- aliased where the config's and the engines' readers look
    ATOL_RANGE,
    MAX_A_MAX0_G,
    MAX_ALPHA,
    MAX_BAND,
    MAX_BLOCK_SIZE,
    MAX_DENSITY,
    MAX_PGA_G,
    MAX_RECORD_SCALE,
    MAX_ROTATION_RATIO,
    MIN_ALPHA,
    MIN_BLOCK_SIZE,
    MIN_DESIGN_RESOLUTION,
    MIN_DESIGN_STEP,
    MIN_PGA_G,
    RTOL_RANGE,
)


@dataclass(frozen=True)
class Quantity:
    """Allowed values of one kind of numeric input, its unit and what it is.

    Parameters
    ----------
    low, high : float or None
        Range ends; None: unbounded on that side (the value must still be finite). [unit]
    unit : str
        Unit as written in messages and schema descriptions ("" or "-" for a ratio).
    description : str
        What the input is, in a few words.
    low_open, high_open : bool
        Whether the ends themselves are excluded.
    integer : bool
        An integer (an ``int``, a numpy integer or a float with an integer value), not any real number.
    optional : bool
        ``None`` is allowed too (its meaning is in the description).
    """

    low: float | None
    high: float | None
    unit: str
    description: str
    low_open: bool = True
    high_open: bool = False
    integer: bool = False
    optional: bool = False

    def check(self, name: str, value):
        """``value`` as a float (an int for an integer quantity, None when optional and None), or
        :class:`~rockstudy.core.validation.InputError` naming ``name``, the value and the range.

        Parameters
        ----------
        name : str
            The input's name as the caller knows it (``"Block.width"``, ``"--kappa-max"``).
        value : object
            The value given.
        """
        if value is None and self.optional:
            return None
        if self.integer:
            low = -lim.MAX_INTEGER - 1 if self.low is None else int(math.ceil(self.low + (1 if self.low_open else 0)))
            high = lim.MAX_INTEGER if self.high is None else int(self.high)
            return v.check_int_range(name, value, low, high)
        return v.check_range(name, value, self.low, self.high, "" if self.unit == "-" else self.unit,
                             low_open=self.low_open, high_open=self.high_open,
                             why="or None" if self.optional else "")

    def limits(self) -> dict:
        """The range as pydantic/annotated-types keywords (``gt``/``ge``, ``lt``/``le``)."""
        out = {}
        kind = int if self.integer else float
        if self.low is not None:
            out["gt" if self.low_open else "ge"] = kind(self.low)
        if self.high is not None:
            out["lt" if self.high_open else "le"] = kind(self.high)
        return out

    def annotated(self):
        """This quantity as a constrained pydantic type (``Annotated[float, Field(...)]``, or ``int``; ``| None``
        when optional), for the config's declarations and their JSON schema."""
        from typing import Annotated, Optional

        from pydantic import Field
        unit = "" if self.unit in ("", "-") else f" [{self.unit}]"
        base = Annotated[int if self.integer else float, Field(description=self.description + unit, **self.limits())]
        return Optional[base] if self.optional else base  # noqa: UP045 -- a runtime type expression



QUANTITIES = {
    # the excitation and its scan
    "frequency_ratio": Quantity(0.0, lim.MAX_FREQUENCY_RATIO, "-", "frequency ratio omega_p/p"),
    "amplitude_ratio": Quantity(0.0, lim.MAX_AMPLITUDE_RATIO, "-", "amplitude ratio a_p/(g tan alpha)"),
    "amplitude_resolution": Quantity(0.0, lim.MAX_AMPLITUDE_RATIO, "-", "width of a threshold's final bracket"),
    "a_max0_g": Quantity(0.0, MAX_A_MAX0_G, "g", "protection level a_max,0"),
    "pga_g": Quantity(0.0, MAX_PGA_G, "g", "peak ground acceleration"),
    "design_pga_g": Quantity(MIN_PGA_G, MAX_PGA_G, "g", "peak ground acceleration of a design stripe", low_open=False),
    "acceleration": Quantity(-lim.MAX_GROUND_ACCELERATION, lim.MAX_GROUND_ACCELERATION, "m/s^2",
                             "ground acceleration amplitude", low_open=False),
    "run_amplitude_ratio": Quantity(0.0, lim.MAX_AMPLITUDE_RATIO, "-", "amplitude ratio a_p/(g tan alpha) of a run",
                                    low_open=False),
    "circular_frequency": Quantity(0.0, None, "rad/s", "circular frequency"),
    "duration": Quantity(0.0, lim.MAX_TIME_SPAN, "s", "duration"),
    "angular_rate": Quantity(None, None, "rad/s", "circular frequency or rate (> 0 where it is a frequency)"),
    "free_time": Quantity(0.0, lim.MAX_FREE_TIME, "s", "free motion after the excitation", low_open=False),
    "record_dt": Quantity(0.0, lim.MAX_TIME_SPAN, "s", "sampling step of a record"),
    "column_dt": Quantity(0.0, lim.MAX_TIME_SPAN, "s", "sampling step of a one-column record (None: a time column)",
                    optional=True),
    "record_scale": Quantity(0.0, MAX_RECORD_SCALE, "-", "factor a record is scaled by"),
    "signed_factor": Quantity(-lim.MAX_RECORD_SCALE, lim.MAX_RECORD_SCALE, "-",
                              "factor (negative: the record reversed)", low_open=False),
    "design_step": Quantity(MIN_DESIGN_STEP, lim.MAX_AMPLITUDE_RATIO, "-", "step of a design block's amplitude scan",
                      low_open=False),
    "design_resolution": Quantity(MIN_DESIGN_RESOLUTION, lim.MAX_AMPLITUDE_RATIO, "-",
                            "resolution of a design block's threshold", low_open=False),
    # the block and its restrainers
    "slenderness": Quantity(MIN_ALPHA, MAX_ALPHA, "rad", "slenderness alpha of a design block", low_open=False),
    "half_diagonal": Quantity(MIN_BLOCK_SIZE, lim.MAX_HALF_DIAGONAL, "m", "half diagonal R of a design block",
                              low_open=False),
    "length": Quantity(MIN_BLOCK_SIZE, MAX_BLOCK_SIZE, "m", "block dimension", low_open=False),
    "density": Quantity(0.0, MAX_DENSITY, "kg/m^3", "mass density"),
    "gravity": Quantity(0.0, lim.MAX_GRAVITY, "m/s^2", "acceleration of gravity"),
    "restitution": Quantity(0.0, 1.0, "-", "coefficient of restitution (None: Housner's, Eq. 14)", low_open=False,
                      optional=True),
    "kappa": Quantity(0.0, lim.MAX_KAPPA, "-", "dimensionless stiffness 4 K b^2/(m g R)", low_open=False),
    "damping_ratio": Quantity(0.0, lim.MAX_DAMPING_RATIO, "-", "damping ratio xi", low_open=False),
    "ultimate_rotation": Quantity(0.0, lim.MAX_ROTATION, "rad", "rotation at which a restrainer breaks (None: alpha)",
                            optional=True),
    # control, sensing and noise
    "sampling_time": Quantity(0.0, lim.MAX_TIME_SPAN, "s", "controller sampling time T_s (0: continuous)",
                              low_open=False),
    "delay": Quantity(0.0, lim.MAX_TIME_SPAN, "s", "actuation delay", low_open=False),
    "band": Quantity(0.0, MAX_BAND, "Hz", "low-pass cut-off (None: no filter)", optional=True),
    "noise_level": Quantity(0.0, 1.0, "-", "noise level N", low_open=False, high_open=True),
    "noise_step": Quantity(0.0, lim.MAX_NOISE_STEP, "s", "sampling step of a noisy record"),
    "noise_span": Quantity(0.0, lim.MAX_TIME_SPAN, "s", "noise after the excitation", low_open=False),
    "seed": Quantity(0.0, lim.MAX_INTEGER, "", "seed of the random numbers", low_open=False, integer=True),
    "realisation": Quantity(0.0, lim.MAX_INTEGER, "", "index of a noise realisation", low_open=False, integer=True),
    "sample_count": Quantity(0.0, lim.MAX_RECORD_SAMPLES, "", "number of samples", low_open=False, integer=True),
    # integration
    "initial_rotation": Quantity(-lim.MAX_ROTATION, lim.MAX_ROTATION, "rad", "initial rotation theta_0",
                                 low_open=False),
    "initial_velocity": Quantity(None, None, "rad/s", "initial rotational velocity"),
    "rest_velocity": Quantity(0.0, None, "rad/s", "|theta_dot+| below which an impact ends the motion",
                        low_open=False, optional=True),
    "rtol": Quantity(*RTOL_RANGE, "-", "relative integration tolerance", low_open=False, optional=True),
    "atol": Quantity(*ATOL_RANGE, "-", "absolute integration tolerance", low_open=False, optional=True),
    # fragility
    "intensity_resolution": Quantity(0.0, lim.MAX_AMPLITUDE_RATIO, "intensity measure",
                               "width of a record threshold's final bracket"),
    "suite_records": Quantity(1, lim.MAX_SUITE_RECORDS, "", "number of records of a suite", low_open=False,
                              integer=True),
    "stripe_count": Quantity(lim.MIN_STRIPES, lim.MAX_LIST_ITEMS, "", "number of PGA levels (stripes)",
                             low_open=False, integer=True),
    # the synthetic record suite (Kanai-Tajimi filtered noise under an envelope)
    "ground_frequency_hz": Quantity(0.0, lim.MAX_GROUND_FREQUENCY_HZ, "Hz", "ground frequency of the filter"),
    "ground_damping": Quantity(0.0, lim.MAX_GROUND_DAMPING, "-", "ground damping ratio of the filter"),
    "envelope_shape": Quantity(0.0, lim.MAX_ENVELOPE_SHAPE, "-", "shape exponent of the envelope"),
    "filter_ratio": Quantity(0.0, 1.0, "-", "frequency of the high-pass filter over the ground frequency",
                             high_open=True),
    "bootstrap": Quantity(0.0, lim.MAX_BOOTSTRAP, "", "bootstrap draws", low_open=False, integer=True),
}
"""Every kind of numeric input, by name."""

ARGUMENTS: dict[str, dict[str, str]] = {}
"""The quantity of each numeric argument of the public classes and functions, by the name the library gives
them (``"Block"`` is :class:`rockstudy.Block`, ``"simulate"`` :func:`rockstudy.simulate`, ``"Record.motion"``
the method): filled by :func:`declares` where each class or function is defined, when its module is imported.
An argument that takes a sequence (``spectrum``'s ``frequency_ratios``) is checked item by item."""

SIZES: dict[tuple[str, str], int] = {}
"""Most items of each sequence argument of the public classes and functions, by (owner, argument): what
bounds the work and the memory a call may take (the engine steps to every record sample); filled by
:func:`declares`."""


def declare(owner: str, sizes: dict | None = None, **arguments: str) -> None:
    """Declare the numeric arguments of ``owner``: the quantity (a key of :data:`QUANTITIES`) of each, and
    the most items of each sequence argument. Used through :func:`declares`.

    Parameters
    ----------
    owner : str
        The class's or function's qualified name (``"Block"``, ``"Record.motion"``).
    sizes : dict, optional
        The most items of each sequence argument, by argument name.
    **arguments : str
        The quantity of each argument, by argument name.

    Raises
    ------
    KeyError
        If a quantity is not one of :data:`QUANTITIES`, or ``owner`` is declared twice differently.
    """
    unknown = sorted(set(arguments.values()) - set(QUANTITIES))
    if unknown:
        raise KeyError(f"{owner}: {', '.join(unknown)} is not a declared quantity (core.quantities.QUANTITIES)")
    if ARGUMENTS.get(owner, arguments) != arguments:
        raise KeyError(f"{owner} is declared twice, differently")
    ARGUMENTS[owner] = dict(arguments)
    for arg, most in (sizes or {}).items():
        SIZES[owner, arg] = int(most)


def declares(sizes: dict | None = None, **arguments: str):
    """Decorator declaring, where a class or function is defined, the quantity of each of its numeric
    arguments (``@declares(width="length", height="length")``) and the most items of each sequence
    argument (``sizes={"acceleration": MAX_RECORD_SAMPLES}``); :func:`check_arguments` then checks them by
    the object's qualified name. The object is returned unchanged.

    Parameters
    ----------
    sizes : dict, optional
        The most items of each sequence argument, by argument name.
    **arguments : str
        The quantity (a key of :data:`QUANTITIES`) of each argument, by argument name.
    """
    def mark(obj):
        declare(obj.__qualname__, sizes, **arguments)
        return obj
    return mark


def check_arguments(owner: str, values: dict, names=None) -> dict:
    """Check each argument of ``owner`` that :data:`ARGUMENTS` declares and ``values`` holds, against its
    quantity. The error names the argument as ``names[argument]`` (the caller's option or config key), else
    as ``"<owner>.<argument>"`` for a class's field (``Block.width``) and by its name for the argument of a
    function or a method.
    Returns the checked values (floats or ints; None where optional).

    Parameters
    ----------
    owner : str
        A declared class or function, by its qualified name (``"Block"``, ``"simulate"`` ...).
    values : dict
        The arguments by name; names the declaration does not list are passed over.
    names : dict, optional
        The caller's name of an argument in messages (``{"kappa_max": "--kappa-max"}``).

    Raises
    ------
    rockstudy.core.validation.InputError
        For the first argument out of its declared type or range, naming it, the value and the range.
    KeyError
        If ``owner`` declares no arguments (its module is not imported, or it has no declaration).
    """
    if owner not in ARGUMENTS:
        raise KeyError(f"{owner} declares no arguments (core.quantities.declares, where it is defined); is its "
                       "module imported?")
    names = names or {}
    # a class's field is Block.width; a function's or a method's argument (Record.motion's scale) is its name
    prefix = f"{owner}." if owner[:1].isupper() and "." not in owner else ""
    out = {}
    for arg, quantity in ARGUMENTS[owner].items():
        if arg in values:
            out[arg] = QUANTITIES[quantity].check(names.get(arg, prefix + arg), values[arg])
    return out
