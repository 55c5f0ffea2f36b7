"""The package's version, written here only (a leaf module: everything that stamps a version imports it
here; ``pyproject.toml`` reads it for the package metadata, and ``CITATION.cff`` states it, checked by
``tests/test_docs.py``)."""

__version__ = "0.3.0.dev0"
