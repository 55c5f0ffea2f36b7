"""rockstudy: seismic rocking of rigid blocks held by on-off controlled anchorages.

Reproduces "Use of overturning spectra in the performance evaluation of on-off
control strategies for rocking objects" (see ``docs/model.md``).
"""
from rockstudy._version import __version__


def _numba_cache_dir() -> str:
    """numba's cache folder for this exact source tree.

    numba invalidates a cached function only when its own file changes, not when a compiled
    function it calls from another module does (``motion.angular_acceleration`` inside
    ``_kernel.engine``): keying the folder by a hash of every module keeps a stale kernel from
    being loaded after any edit. ``NUMBA_CACHE_DIR`` in the environment still wins.
    """
    import hashlib
    from pathlib import Path

    root = Path(__file__).parent
    digest = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        digest.update(path.relative_to(root).as_posix().encode())
        digest.update(path.read_bytes())
    return str(root / "__pycache__" / f"numba-{digest.hexdigest()[:16]}")


def _configure_numba_cache():
    import os

    import numba

    if not os.environ.get("NUMBA_CACHE_DIR"):
        numba.config.CACHE_DIR = _numba_cache_dir()


_configure_numba_cache()

from rockstudy.analysis.scenario import Scenario  # noqa: E402
from rockstudy.analysis.spectra import (  # noqa: E402
    AmplitudeGrid,
    ThresholdResult,
    frequency_grid,
    spectrum,
    threshold,
)
from rockstudy.engine.outcome import Outcome  # noqa: E402
from rockstudy.engine.simulate import simulate  # noqa: E402
from rockstudy.engine.simulation_result import SimulationResult  # noqa: E402
from rockstudy.model.anchorage import Anchorage  # noqa: E402
from rockstudy.model.block import BLOCK_PRESETS, GRAVITY, Block  # noqa: E402
from rockstudy.model.control import STRATEGIES, Control  # noqa: E402
from rockstudy.model.excitation import GroundMotion  # noqa: E402

__all__ = ["Block", "BLOCK_PRESETS", "GRAVITY", "Anchorage", "Control", "STRATEGIES", "GroundMotion", "Outcome",
           "SimulationResult", "AmplitudeGrid", "Scenario", "frequency_grid", "simulate", "spectrum", "threshold",
           "ThresholdResult",
           "__version__"]
