"""The studies beyond the paper as the workflow runs them: the config's ``beyond:`` section
(probability of overturning over the noise realisations, fragility over a record suite) checked
across keys, before any job runs.
"""
from __future__ import annotations

from rockstudy.core import validation


def check_config(section: dict, config: dict) -> None:
    """The ``beyond:`` section agrees with the rest of the study ``config``.

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) naming the key, the value and what is allowed.
    """
    levels = config["noise_levels"]
    for level in section["probability"]["noise_levels"]:
        if level not in levels:
            raise validation.InputError(f"beyond.probability.noise_levels: {level!r} is not one of noise_levels "
                                        f"({', '.join(levels)})")
    if "FS" not in section["fragility"]["strategies"]:
        raise validation.InputError("beyond.fragility.strategies: FS is needed as the reference of the median shift")
