"""rockstudy: seismic rocking of rigid blocks held by on-off controlled anchorages.

Reproduces "Use of overturning spectra in the performance evaluation of on-off
control strategies for rocking objects" (see ``docs/model.md``).
"""
from importlib.metadata import PackageNotFoundError, version as _version

try:
    __version__ = _version("rockstudy")
except PackageNotFoundError:  # running from a source tree without install
    __version__ = "0.0.0+unknown"

from .block import Block, BLOCK_PRESETS, GRAVITY  # noqa: E402
from .anchorage import Anchorage  # noqa: E402
from .control import Control, STRATEGIES  # noqa: E402
from .excitation import GroundMotion  # noqa: E402
from .outcome import Outcome  # noqa: E402
from .result import SimulationResult  # noqa: E402
from .spectra import AmplitudeGrid, Scenario, frequency_grid, spectrum, threshold  # noqa: E402
# the function, not the module: ``rockstudy.simulate(...)``; the module stays importable as
# ``from rockstudy.simulate import pack_parameters``
from .simulate import simulate  # noqa: E402

__all__ = ["Block", "BLOCK_PRESETS", "GRAVITY", "Anchorage", "Control", "STRATEGIES", "GroundMotion", "Outcome",
           "SimulationResult", "AmplitudeGrid", "Scenario", "frequency_grid", "simulate", "spectrum", "threshold",
           "__version__"]
