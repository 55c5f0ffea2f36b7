"""Source fingerprints: SHA-256 hashes of rockstudy's own sources by layer, which the workflow passes to
its rules as parameters so that Snakemake reruns the jobs whose code changed."""
from __future__ import annotations

import hashlib
from pathlib import Path

SIMULATION_LAYERS = ("core", "model", "engine", "analysis")
"""The subpackages whose code can change a simulated number: the workflow reruns every simulation when
one of them changes (the study's bookkeeping, the figures and the CLI are fingerprinted on their own)."""

NOT_SIMULATED = ("engine/reference",)
"""Folders inside :data:`SIMULATION_LAYERS` that no study result runs: the scipy reference engine, which
the tests compare with the fast engine."""


def fingerprint_files(*parts: str) -> list[Path]:
    """The source files :func:`source_fingerprint` hashes, relative to the package, in a fixed order.

    Parameters
    ----------
    *parts : str
        Subpackage folders (``"engine"``) or module files (``"plotting.py"``), relative to the package;
        none given: :data:`SIMULATION_LAYERS` without :data:`NOT_SIMULATED`.
    """
    root = Path(__file__).resolve().parents[1]
    files = []
    for part in parts or SIMULATION_LAYERS:
        target = root / part
        if not target.exists():
            raise ValueError(f"source_fingerprint: {part!r} is not a folder or module of rockstudy")
        for path in sorted(target.rglob("*.py")) if target.is_dir() else [target]:
            name = path.relative_to(root).as_posix()
            if parts or not any(name.startswith(f"{skip}/") for skip in NOT_SIMULATED):
                files.append(Path(name))
    return files


def source_fingerprint(*parts: str) -> str:
    """SHA-256 of the package's sources under ``parts``: subpackage folders (``"engine"``) or module files
    (``"plotting.py"``), relative to the package; none given: :data:`SIMULATION_LAYERS` without
    :data:`NOT_SIMULATED`.

    Snakemake passes it to a rule as a parameter, so the rule reruns when that code changes. Folders,
    not file lists: a new module is covered by its layer's fingerprint without editing the workflow.

    Parameters
    ----------
    *parts : str
        Subpackage folders or module files as in :func:`fingerprint_files`; none given: the simulation
        layers.
    """
    root = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256()
    for name in fingerprint_files(*parts):
        digest.update(name.as_posix().encode())
        digest.update((root / name).read_bytes())
    return digest.hexdigest()
