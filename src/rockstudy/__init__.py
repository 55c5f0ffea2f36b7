"""rockstudy: seismic rocking of rigid blocks held by on-off controlled anchorages.

Reproduces "Use of overturning spectra in the performance evaluation of on-off
control strategies for rocking objects" (see ``docs/model.md``).

The names of the public API are imported on first use (``rockstudy.simulate`` or ``from rockstudy
import simulate``), so that ``import rockstudy`` and the modules that only read and write datasets
load neither numba nor the compiled engine.
"""
import importlib
import importlib.util
import os
import sys

from rockstudy._version import __version__

_PUBLIC = {
    "Scenario": "rockstudy.analysis.scenario",
    "JosResult": "rockstudy.analysis.jos",
    "jos": "rockstudy.analysis.jos",
    "AmplitudeGrid": "rockstudy.analysis.spectra",
    "ThresholdResult": "rockstudy.analysis.spectra",
    "frequency_grid": "rockstudy.analysis.spectra",
    "spectrum": "rockstudy.analysis.spectra",
    "threshold": "rockstudy.analysis.spectra",
    "Outcome": "rockstudy.engine.outcome",
    "simulate": "rockstudy.engine.simulate",
    "SimulationResult": "rockstudy.engine.simulation_result",
    "Anchorage": "rockstudy.model.anchorage",
    "BLOCK_PRESETS": "rockstudy.model.block",
    "GRAVITY": "rockstudy.model.block",
    "Block": "rockstudy.model.block",
    "STRATEGIES": "rockstudy.model.control",
    "Control": "rockstudy.model.control",
    "GroundMotion": "rockstudy.model.excitation",
}
"""Where each name of the public API is defined (imported by :func:`__getattr__` on first use)."""

_SUBPACKAGES = ("analysis", "core", "engine", "model", "studies", "plotting", "report", "cli")

__all__ = ["Block", "BLOCK_PRESETS", "GRAVITY", "Anchorage", "Control", "STRATEGIES", "GroundMotion", "Outcome",
           "SimulationResult", "AmplitudeGrid", "Scenario", "frequency_grid", "simulate", "spectrum", "threshold",
           "ThresholdResult", "jos", "JosResult",
           "__version__"]


def _import(module: str):
    """``module`` imported; a dependency that fails to import is one line naming it (ImportError)."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        failing = exc.name or ""
        if failing.startswith("rockstudy"):
            raise
        raise ImportError(f"rockstudy: {module} needs {failing or 'a dependency'}, which failed to import "
                          f"({str(exc).splitlines()[0] if str(exc) else type(exc).__name__}); reinstall it "
                          "(pip install -e .)") from None


def __getattr__(name):
    """The public API and the subpackages, imported on first use (PEP 562)."""
    if name in _PUBLIC:
        value = getattr(_import(_PUBLIC[name]), name)
        globals()[name] = value  # the next lookup is an ordinary attribute
        return value
    if name in _SUBPACKAGES:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__) | set(_SUBPACKAGES))


def _source_digest(root) -> str:
    """A hash of every module under ``root``: the key of numba's cache folder."""
    import hashlib

    digest = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        digest.update(path.relative_to(root).as_posix().encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def _writable(folder) -> bool:
    """Whether ``folder`` exists or can be made, and a file can be created in it (tried, then removed)."""
    import tempfile

    try:
        os.makedirs(folder, exist_ok=True)
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".probe-")
        os.close(fd)
        os.remove(probe)
    except OSError:
        return False
    return True


def _numba_cache_dir(root=None) -> str:
    """numba's cache folder for this exact source tree: the package's ``__pycache__``, else (a read-only
    install) the user's cache folder (``$XDG_CACHE_HOME`` or ``~/.cache``), else the temporary folder --
    the first that can be written. With none writable, ImportError says to set ``NUMBA_CACHE_DIR``.

    numba invalidates a cached function only when its own file changes, not when a compiled
    function it calls from another module does (``motion.angular_acceleration`` inside
    ``_kernel.engine``): keying the folder by a hash of every module keeps a stale kernel from
    being loaded after any edit. ``NUMBA_CACHE_DIR`` in the environment still wins.

    Parameters
    ----------
    root : pathlib.Path, optional
        The package's folder (default: this package's).
    """
    import tempfile
    from pathlib import Path

    root = Path(__file__).parent if root is None else Path(root)
    name = f"numba-{_source_digest(root)}"
    user = Path(os.environ.get("XDG_CACHE_HOME") or Path("~/.cache").expanduser())
    try:
        temporary = Path(tempfile.gettempdir())
    except FileNotFoundError:  # no usable temporary folder at all
        temporary = Path("/tmp")
    candidates = [root / "__pycache__" / name, user / "rockstudy" / name,
                  temporary / f"rockstudy-{os.getuid() if hasattr(os, 'getuid') else 0}" / name]
    for folder in candidates:
        if _writable(folder):
            return str(folder)
    raise ImportError(f"rockstudy: no writable folder for numba's compiled cache ({', '.join(map(str, candidates))}); "
                      "set NUMBA_CACHE_DIR to a writable folder")


def _set_numba_cache_dir(numba) -> None:
    if not os.environ.get("NUMBA_CACHE_DIR"):
        numba.config.CACHE_DIR = _numba_cache_dir()


class _OnNumbaImport:
    """Import hook (a ``sys.meta_path`` finder) that points numba's cache at :func:`_numba_cache_dir`
    as soon as numba is imported, before any module can decorate a compiled function, and then
    leaves ``sys.meta_path``."""

    def find_spec(self, name, path=None, target=None):
        if name != "numba":
            return None
        sys.meta_path.remove(self)
        spec = importlib.util.find_spec("numba")  # what the other finders give
        if spec is None or spec.loader is None or not hasattr(spec.loader, "exec_module"):
            return spec
        exec_module = spec.loader.exec_module  # the loader is this import's own instance

        def exec_then_configure(module):
            exec_module(module)
            _set_numba_cache_dir(module)

        spec.loader.exec_module = exec_then_configure
        return spec


def _configure_numba_cache() -> None:
    """numba reads its cache folder when a ``@njit(cache=True)`` function is decorated: set it now if
    numba is already imported, else the moment it is (without importing numba here)."""
    if "numba" in sys.modules:
        _set_numba_cache_dir(sys.modules["numba"])
    elif not any(isinstance(finder, _OnNumbaImport) for finder in sys.meta_path):
        sys.meta_path.insert(0, _OnNumbaImport())


_configure_numba_cache()
