"""The study's parameters from plain dictionaries (the parsed ``config.yaml`` of the workflow, or
any dict a user builds): a block, a scenario, the grids, the jobs of a spectrum, the noise-free
level. Each parser refuses a bad value with :class:`rockstudy.core.validation.InputError` naming
the config key. Amplitudes are ratios a_p/(g·tanα), frequencies ratios ω_p/p; a_max,0 is given in
units of g.
"""
from __future__ import annotations

from dataclasses import fields
from typing import TYPE_CHECKING

import numpy as np

from rockstudy.analysis.jos import a_max0_ratio  # noqa: F401 (the scripts' a_max,0 in g as a ratio)
from rockstudy.core import validation
from rockstudy.core.quantities import check_arguments
from rockstudy.model.block import BLOCK_PRESETS, Block

if TYPE_CHECKING:

    from rockstudy.analysis.scenario import Scenario
    from rockstudy.analysis.spectra import AmplitudeGrid

# The parsers of scenarios and grids import the simulation layers where they are called, so that a job that
# only reads settings (tables, figures) does not load the compiled model and engine.

BLOCK_FIELDS = tuple(f.name for f in fields(Block))
"""The keys of a block given by its dimensions."""

__all__ = ["block_from_dict", "scenario_from_dict", "amplitude_grid", "frequency_ratios", "intensity_levels",
           "realisation_chunks", "noise_free_level", "a_max0_ratio", "grid_size_points",
           "reading_from_dict"]  # noqa: F822 (from rockstudy.model.noise, by __getattr__)


def __getattr__(name):
    if name == "reading_from_dict":  # re-exported from rockstudy.model.noise, on first use
        from rockstudy.model.noise import reading_from_dict
        return reading_from_dict
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def block_from_dict(spec: dict, names: dict | None = None) -> Block:
    """A :class:`Block` from ``{"preset": name}`` or from its dimensions (``width``, ``height``, ...).

    Parameters
    ----------
    spec : dict
        ``{"preset": name}`` (a key of :data:`~rockstudy.model.block.BLOCK_PRESETS`), or the block's
        dimensions: ``width``, ``height``, ``depth`` [m] and optionally ``density``, ``gravity``,
        ``restitution`` (None: Eq. 14).
    names : dict, optional
        The caller's name of each dimension in error messages (``{"width": "--width"}``); one missing from it
        is named ``block.<field>``.
    """
    spec = dict(spec)
    preset = spec.pop("preset", None)
    if preset is not None:
        if preset not in BLOCK_PRESETS:
            raise ValueError(f"block.preset must be one of {', '.join(BLOCK_PRESETS)}, got {preset!r}")
        if spec:
            raise ValueError(f"block: give either a preset or dimensions, not both (got {sorted(spec)})")
        return BLOCK_PRESETS[preset]
    unknown = set(spec) - set(BLOCK_FIELDS)
    if unknown:
        raise validation.InputError(f"block: unknown key(s) {sorted(unknown)}; allowed: preset or "
                                    f"{', '.join(BLOCK_FIELDS)}")
    names = {"block": "block", **{field: (names or {}).get(field, f"block.{field}") for field in BLOCK_FIELDS}}
    missing = {"width", "height", "depth"} - set(spec)
    if missing:  # each value given is named before what is missing (no block is made to check them)
        check_arguments("Block", spec, names)
        raise validation.InputError(f"block: missing key(s) {sorted(missing)}; give a preset or width, height "
                                    "and depth")
    return Block(**spec, names=names)  # checks each field once, naming it, then the proportions (Eq. 14)


def scenario_from_dict(spec: dict) -> Scenario:
    """A :class:`Scenario` from ``block``, ``anchorage``, ``control``, ``noise`` dicts and scalar settings.

    Parameters
    ----------
    spec : dict
        ``block`` (for :func:`block_from_dict`), optionally ``anchorage`` and ``control`` (the fields of
        :class:`~rockstudy.model.anchorage.Anchorage` and :class:`~rockstudy.model.control.Control`), ``noise``
        (``step``, ``rescale``, ``level_means``, ``band``, ``span``;
        :class:`rockstudy.model.noise.NoiseReading`; absent: :data:`rockstudy.model.noise.DEFAULT_READING`) and
        the scalar fields of :class:`~rockstudy.analysis.scenario.Scenario` (``excitation``, ``noise_level``,
        ``seed``, ``overturn_criterion``, ``free_time``).
    """
    from rockstudy.analysis.scenario import Scenario
    from rockstudy.model.anchorage import Anchorage
    from rockstudy.model.control import Control
    from rockstudy.model.noise import reading_from_dict

    spec = dict(spec)
    block = block_from_dict(spec.pop("block"))
    anchorage, control = spec.pop("anchorage", {}), spec.pop("control", {})
    try:  # each checked once, at construction, naming its config key
        anchorage = Anchorage(**anchorage, names={f.name: f"anchorage.{f.name}" for f in fields(Anchorage)})
        control = Control(**control, names={f.name: f"control.{f.name}" for f in fields(Control)})
    except ValueError as exc:
        raise validation.InputError(str(exc)) from None
    noise = reading_from_dict(spec.pop("noise", None), key="noise")
    return Scenario(block, anchorage, control, noise=noise, **spec)


def amplitude_grid(spec: dict, key: str = "amplitude_grid") -> AmplitudeGrid:
    """:class:`AmplitudeGrid` from ``start``, ``stop``, ``step``, ``resolution`` (ratios a_p/(g·tanα)),
    refused (naming ``<key>.<field>``) beyond the limits of :mod:`rockstudy.core.validation`.

    Parameters
    ----------
    spec : dict
        ``start``, ``stop``, ``step`` and ``resolution``, ratios a_p/(g·tanα). [-]
    key : str, default "amplitude_grid"
        The config key the messages name.
    """
    validation.check_amplitude_grid(spec["start"], spec["stop"], spec["step"], spec["resolution"],
                                    names=tuple(f"{key}.{field}" for field in ("start", "stop", "step", "resolution")))
    from rockstudy.analysis.spectra import AmplitudeGrid

    return AmplitudeGrid(**spec)


def frequency_ratios(spec: dict, key: str = "frequency_grid") -> np.ndarray:
    """Frequency ratios ω_p/p from ``start``, ``stop``, ``step``, refused (naming ``<key>.<field>``)
    above :data:`rockstudy.core.validation.MAX_GRID_POINTS` points before the grid is built. [-]

    Parameters
    ----------
    spec : dict
        ``start``, ``stop`` and ``step`` of the ratios ω_p/p. [-]
    key : str, default "frequency_grid"
        The config key the messages name.
    """
    validation.check_grid(key, spec["start"], spec["stop"], spec["step"], high=validation.MAX_FREQUENCY_RATIO)
    from rockstudy.analysis.spectra import frequency_grid

    return frequency_grid(**spec)


def intensity_levels(spec: dict, key: str = "beyond.fragility.intensity_levels") -> np.ndarray:
    """Intensity levels (the fragility's stripes) from ``start``, ``stop``, ``step``, refused (naming
    ``<key>.<field>``) like :func:`frequency_ratios`. [-]

    Parameters
    ----------
    spec : dict
        ``start``, ``stop`` and ``step`` of the levels. [-]
    key : str, default "beyond.fragility.intensity_levels"
        The config key the messages name.
    """
    validation.check_grid(key, spec["start"], spec["stop"], spec["step"], high=validation.MAX_AMPLITUDE_RATIO)
    from rockstudy.analysis.spectra import frequency_grid

    return frequency_grid(**spec)


def realisation_chunks(n_realisations: int, per_job: int, noisy: bool = True) -> list[list[int]]:
    """Realisation indices split into jobs of at most ``per_job`` (one job [0] without noise).

    Parameters
    ----------
    n_realisations : int
        Number of noise realisations, >= 1.
    per_job : int
        Largest number of realisations in one job, >= 1.
    noisy : bool, default True
        False for the noise-free level: one job with realisation 0.
    """
    if n_realisations < 1 or per_job < 1:
        raise ValueError(f"n_realisations and per_job must be >= 1, got {n_realisations}, {per_job}")
    if not noisy:
        return [[0]]
    return [list(range(i, min(i + per_job, n_realisations))) for i in range(0, n_realisations, per_job)]


def noise_free_level(levels: dict) -> str:
    """Name of the noise level whose value is 0 (the paper's R000).

    Parameters
    ----------
    levels : dict
        Noise level name -> noise level (noise energy over baseline energy); exactly one is 0. [-]
    """
    names = [name for name, value in levels.items() if value == 0]
    if len(names) != 1:
        raise ValueError(f"noise_levels needs exactly one level equal to 0 (R000), got {levels!r}")
    return names[0]


def grid_size_points(spec: dict) -> int:
    """Number of points of an amplitude grid ``{start, stop, step}`` (the simulations of one map row).

    Parameters
    ----------
    spec : dict
        ``start``, ``stop`` and ``step`` of the amplitude grid (other keys are ignored). [-]
    """
    return validation.grid_size(spec["start"], spec["stop"], spec["step"])
