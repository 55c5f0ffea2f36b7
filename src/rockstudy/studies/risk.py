"""The config's ``risk:`` section (optional): its check before any job runs, which reads every hazard file it
names. The risk itself is computed by :mod:`rockstudy.analysis.risk_sites`; the section's keys are declared by
:class:`rockstudy.studies.config_model.Risk`.
"""
from __future__ import annotations

import warnings

from rockstudy.analysis.ground_motion import check_range, check_scenario
from rockstudy.analysis.hazard import read_hazard_sites
from rockstudy.core import validation
from rockstudy.core.risk_inputs import DEFAULT_GMM
from rockstudy.studies import config_model


def check_config(section: dict, key: str = "risk") -> dict:
    """The config's ``risk:`` section: its declaration (:class:`rockstudy.studies.config_model.Risk`: every value
    in range, no unknown key), at least one site, every hazard file readable. Returns every site of each hazard
    file (a list of :class:`~rockstudy.analysis.hazard.HazardSite`) by the file's name.

    Parameters
    ----------
    section : dict
        The ``risk:`` section: ``scenarios``, ``hazard_curves`` (name: file path), ``hazard_units`` (name: the
        unit of that file's PGA levels, when not g or not stated by the file) and the other keys of
        :class:`rockstudy.studies.config_model.Risk`.
    key : str, default "risk"
        Where the section sits in the config: errors name ``<key>.<entry>``.

    Raises
    ------
    ValueError
        (:class:`~rockstudy.core.validation.InputError`) naming ``<key>.<entry>``.
    """
    config_model.check_config(section, config_model.Risk, key)
    scenarios, curves = section.get("scenarios") or {}, section.get("hazard_curves") or {}
    units = section.get("hazard_units") or {}
    if not scenarios and not curves:
        raise validation.InputError(f"{key}: give at least one scenario or hazard curve")
    for name, scenario in scenarios.items():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            check_range(check_scenario(scenario, f"{key}.scenarios.{name}"), section.get("gmm") or DEFAULT_GMM,
                        f"{key}.scenarios.{name}", bool(section.get("outside_gmm_range")))
    unknown = sorted(set(units) - set(curves))
    if unknown:
        raise validation.InputError(f"{key}.hazard_units: {', '.join(unknown)} is not a hazard curve's name "
                                    f"({', '.join(curves) or 'none given'})")
    return {name: read_hazard_sites(path, f"{key}.hazard_curves.{name}", units.get(name))
            for name, path in curves.items()}
