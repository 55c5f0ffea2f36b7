"""The installed package's version (a leaf module: everything that stamps a version imports it here)."""
from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as _version

try:
    __version__ = _version("rockstudy")
except PackageNotFoundError:  # running from a source tree without install
    __version__ = "0.0.0+unknown"
