"""Median PGA and its log standard deviation for an earthquake scenario, from a published ground-motion
model (GMM) through pygmm [1]_: the NGA-West2 models of Abrahamson, Silva and Kamai (ASK14), Boore,
Stewart, Seyhan and Atkinson (BSSA14), Campbell and Bozorgnia (CB14) and Chiou and Youngs (CY14).

A scenario is magnitude ``mag``, closest distance to the rupture ``dist_rup`` [km] and ``v_s30`` [m/s];
what a model needs besides, unless given, is taken from
:data:`rockstudy.core.risk_inputs.SCENARIO_DEFAULTS` (a vertical
strike-slip rupture reaching the surface, the site off its end: R_JB = R_X = R_rup), and pygmm fills
its own defaults (region, basin depths, rupture width). :func:`pga` returns every value the model
used, defaults included.

References
----------
.. [1] A. R. Kottke. pygmm: ground motion models implemented in Python. https://github.com/arkottke/pygmm
"""
from __future__ import annotations

import math
import warnings

from rockstudy.core import validation
from rockstudy.core.risk_inputs import (
    DEFAULT_GMM,
    GMM_MAX_MAG_BY_MECHANISM,
    GMM_RANGES,
    GMMS,
    MECHANISMS,
    SCENARIO_DEFAULTS,
    SCENARIO_INPUTS,
    SCENARIO_REQUIRED,
)


def check_scenario(scenario: dict, name: str = "scenario") -> dict:
    """The scenario with the defaults filled in, checked against the declared ranges
    (:mod:`rockstudy.core.risk_inputs`).

    Parameters
    ----------
    scenario : dict
        ``mag``, ``dist_rup`` [km], ``v_s30`` [m/s] and optionally ``mechanism``, ``dip`` [deg],
        ``depth_tor``, ``dist_jb``, ``dist_x`` [km].
    name : str, default "scenario"
        The scenario's name in error messages (e.g. its config key).

    Raises
    ------
    ValueError
        (:class:`~rockstudy.core.validation.InputError`) naming ``name.<key>`` for a missing, unknown or
        out-of-range value.
    """
    missing = [k for k in SCENARIO_REQUIRED if k not in scenario]
    if missing:
        raise validation.InputError(f"{name}: missing {', '.join(missing)} (a scenario gives "
                                    f"{', '.join(SCENARIO_REQUIRED)})")
    known = set(SCENARIO_INPUTS) | {"mechanism"}
    unknown = sorted(set(scenario) - known)
    if unknown:
        raise validation.InputError(f"{name}: unknown key(s) {', '.join(unknown)}; allowed: {', '.join(sorted(known))}")
    used = {**SCENARIO_DEFAULTS, **scenario}
    used.setdefault("dist_jb", used["dist_rup"])
    used.setdefault("dist_x", used["dist_jb"])
    if used["mechanism"] not in MECHANISMS:
        raise validation.InputError(f"{name}.mechanism = {used['mechanism']!r} is not allowed: one of "
                                    f"{', '.join(MECHANISMS)}")
    for key, bound in SCENARIO_INPUTS.items():
        used[key] = bound.check(f"{name}.{key}", used[key])
    # a site on the ground surface: the rupture is no nearer than its top, and no nearer than its surface projection
    if used["dist_jb"] > used["dist_rup"]:
        raise validation.InputError(f"{name}: dist_jb = {used['dist_jb']:g} km exceeds dist_rup = {used['dist_rup']:g}"
                                    " km; the closest distance to the rupture is at least the Joyner-Boore distance")
    if used["depth_tor"] > used["dist_rup"]:
        raise validation.InputError(f"{name}: depth_tor = {used['depth_tor']:g} km exceeds dist_rup = "
                                    f"{used['dist_rup']:g} km; a site on the surface is no nearer than the top")
    if used["dip"] == 90 and abs(used["dist_x"]) > used["dist_jb"]:  # R_X: to the trace's line, R_JB: to the trace
        raise validation.InputError(f"{name}: |dist_x| = {abs(used['dist_x']):g} km exceeds dist_jb = "
                                    f"{used['dist_jb']:g} km, which a vertical rupture does not allow")
    return used


class GmmRangeWarning(UserWarning):
    """A scenario lies outside its ground-motion model's published range (answered on request)."""


def range_problems(used: dict, gmm: str) -> list[str]:
    """What of a scenario lies outside the published range of ``gmm``
    (:data:`rockstudy.core.limits.GMM_RANGES`, :data:`~rockstudy.core.limits.GMM_MAX_MAG_BY_MECHANISM`).

    Parameters
    ----------
    used : dict
        The scenario with its defaults (:func:`check_scenario`).
    gmm : str
        A key of :data:`rockstudy.core.risk_inputs.GMMS`.

    Returns
    -------
    list of str
        One sentence per value outside the range; empty when the scenario lies within it.
    """
    problems = []
    for key, (low, high) in GMM_RANGES[gmm].items():
        if key in used and not low <= used[key] <= high:
            problems.append(f"{key} = {used[key]:g} lies outside {gmm}'s range {low:g} to {high:g}")
    mechanism = used.get("mechanism")
    top = GMM_MAX_MAG_BY_MECHANISM.get(gmm, {}).get(mechanism) if isinstance(mechanism, str) else None
    if top is not None and used["mag"] > top:
        problems.append(f"mag = {used['mag']:g} exceeds {gmm}'s {top:g} for mechanism {used['mechanism']}")
    return problems


def check_range(used: dict, gmm: str, name: str = "scenario", outside_range: bool = False) -> list[str]:
    """Refuse a scenario outside the published range of ``gmm``, or (``outside_range``) warn
    (:class:`GmmRangeWarning`) and return the sentences.

    Parameters
    ----------
    used : dict
        The scenario with its defaults (:func:`check_scenario`).
    gmm : str
        A key of :data:`rockstudy.core.risk_inputs.GMMS`.
    name : str, default "scenario"
        The scenario's name in messages.
    outside_range : bool, default False
        Answer outside the range with a warning instead of refusing.
    """
    problems = range_problems(used, gmm)
    if problems and not outside_range:
        raise validation.InputError(f"{name}: {'; '.join(problems)} (the model's published range; a model is not "
                                    "valid outside it)")
    for text in problems:
        warnings.warn(f"{name}: {text}: the model is used outside its published range", GmmRangeWarning,
                      stacklevel=2)
    return problems


def pga(scenario: dict, gmm: str = DEFAULT_GMM, *, name: str = "scenario",
        outside_range: bool = False) -> tuple[float, float, dict]:
    """Median PGA and its log standard deviation for a scenario, from the model ``gmm`` (pygmm).

    Parameters
    ----------
    scenario : dict
        ``mag``, ``dist_rup`` [km], ``v_s30`` [m/s] and optionally ``mechanism``, ``dip`` [deg],
        ``depth_tor``, ``dist_jb``, ``dist_x`` [km] (:func:`check_scenario`).
    gmm : str
        A key of :data:`rockstudy.core.risk_inputs.GMMS`.
    name : str, default "scenario"
        The scenario's name in messages.
    outside_range : bool, default False
        A scenario outside the model's published range (:func:`check_range`) is refused, or with True answered
        with a :class:`GmmRangeWarning`.

    Returns
    -------
    median_pga_g : float
        [g]
    ln_std : float
        Total standard deviation of ln PGA. [-]
    used : dict
        Every scenario value the model used, pygmm's defaults included.
    """
    if gmm not in GMMS:
        raise validation.InputError(f"gmm = {gmm!r} is not allowed: one of {', '.join(GMMS)}")
    used = check_scenario(scenario, name)
    check_range(used, gmm, name, outside_range)
    try:
        import pygmm
    except ImportError:  # pragma: no cover - pygmm is a dependency
        raise validation.InputError("the scenario risk needs pygmm: pip install pygmm") from None
    model = getattr(pygmm, GMMS[gmm])(pygmm.Scenario(**used))
    # the values the model used (pygmm keeps them, with its own defaults, on the model)
    used = {k: _plain(v) for k, v in model._scenario.items()}
    median, sigma = float(model.pga), float(model.ln_std_pga)
    if not (math.isfinite(median) and median > 0 and math.isfinite(sigma) and sigma >= 0):
        raise validation.InputError(f"{gmm} gives no finite PGA for the scenario {used}")
    return median, sigma, used


def _plain(value):
    """A JSON-ready scalar (numpy numbers as Python floats)."""
    if value is None or isinstance(value, (bool, str)):
        return value
    try:
        return float(value)
    except (TypeError, ValueError):
        return str(value)
