"""The environment, generated over its ways of failing:

* numba's cache folder: every combination of the three places it may go (the package's ``__pycache__``, the
  user's cache folder, the temporary folder) being unwritable -- a regular file where the folder must be, which
  even root cannot write into -- gives the first writable one, or, with none, one line saying to set
  ``NUMBA_CACHE_DIR``;
* a dependency that fails to import (a broken compiled library) behind each public name is one line naming
  the dependency, not a traceback from inside it.
"""
from __future__ import annotations

import itertools
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

import rockstudy

SRC = Path(rockstudy.__file__).parents[1]
PLACES = ("package", "user", "temporary")


def _block(folder: Path) -> None:
    """Make ``folder`` impossible to create: a regular file stands where its parent must be."""
    folder.parent.parent.mkdir(parents=True, exist_ok=True)
    folder.parent.write_text("a file, not a folder")


@pytest.mark.parametrize("blocked", [b for n in range(4) for b in itertools.combinations(PLACES, n)],
                         ids=lambda b: "+".join(b) or "none")
def test_the_cache_goes_to_the_first_writable_place(blocked, tmp_path, monkeypatch):
    root = tmp_path / "pkg"
    root.mkdir()
    (root / "module.py").write_text("x = 1\n")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "user" / "cache"))
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path / "tmp" / "t"))
    places = {"package": root / "__pycache__" / "x", "user": tmp_path / "user" / "cache" / "rockstudy" / "x",
              "temporary": tmp_path / "tmp" / "t" / f"rockstudy-{os.getuid()}" / "x"}
    for place in blocked:
        _block(places[place])
    free = [p for p in PLACES if p not in blocked]
    if not free:
        with pytest.raises(ImportError) as refused:
            rockstudy._numba_cache_dir(root)
        assert "NUMBA_CACHE_DIR" in str(refused.value) and len(str(refused.value).splitlines()) == 1
        return
    chosen = Path(rockstudy._numba_cache_dir(root))
    assert chosen.parent == places[free[0]].parent, (chosen, free[0])
    assert os.access(chosen, os.W_OK) and chosen.name.startswith("numba-")


DEPENDENCIES = ("numba", "scipy", "xarray", "netCDF4", "numpy")


@pytest.mark.parametrize("dependency", DEPENDENCIES)
def test_a_dependency_that_fails_to_import_is_one_line_naming_it(dependency, tmp_path):
    """Every public name, with ``dependency`` broken: it loads (its module does not need it), or one line
    names the dependency."""
    broken = tmp_path / dependency
    broken.mkdir()
    (broken / "__init__.py").write_text(f"raise ImportError('libcompiled-7.so.1: cannot open shared object file', "
                                        f"name={dependency!r})\n")
    code = ("import rockstudy\n"
            "for name in sorted(rockstudy._PUBLIC):\n"
            "    try:\n"
            "        getattr(rockstudy, name)\n"
            "        print(name, 'loaded')\n"
            "    except ImportError as exc:\n"
            "        print(name, 'refused', repr(str(exc)))\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tmp_path), str(SRC)])}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300)
    rows = out.stdout.strip().splitlines()
    assert len(rows) == len(rockstudy._PUBLIC), (out.stdout, out.stderr[-2000:])
    refused = [row for row in rows if " refused " in row]
    for row in refused:
        message = row.split(" refused ", 1)[1]
        assert dependency in message and "\\n" not in message, row
    if dependency in ("numba", "numpy"):
        assert refused, "the engine needs numba and numpy"
