"""The command line at its environment's failures, run as a user runs it (a subprocess): a dependency that fails to
import at start is one line naming it, and an output that cannot be written is one line (exit 2) saying where the
computed result is kept; never a traceback."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

import rockstudy

SRC = Path(rockstudy.__file__).parents[1]
COMMANDS = {"spectrum": ["spectrum", "--frequency-start", "2", "--frequency-stop", "2", "--max-amplitude-ratio", "1.5",
                         "--amplitude-step", "0.3", "--resolution", "0.3"],
            "simulate": ["simulate", "--frequency-ratio", "2", "--amplitude-ratio", "1.4"]}


def _run(args, tmp_path, pythonpath=(), code=None):
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([*map(str, pythonpath), str(SRC)]),
           "TMPDIR": str(tmp_path / "tmp")}
    (tmp_path / "tmp").mkdir(exist_ok=True)
    command = [sys.executable, "-c", code, *args] if code else [sys.executable, "-m", "rockstudy.cli", *args]
    return subprocess.run(command, capture_output=True, text=True, env=env, timeout=300, cwd=tmp_path)


@pytest.mark.parametrize("dependency", ["numpy", "numba", "xarray"])
@pytest.mark.parametrize("command", ["spectrum", "simulate"])
def test_a_dependency_that_fails_to_import_is_one_line_naming_it(dependency, command, tmp_path):
    broken = tmp_path / "fake" / dependency
    broken.mkdir(parents=True)
    (broken / "__init__.py").write_text(f"raise ImportError('libcompiled-7.so.1: cannot open shared object file', "
                                        f"name={dependency!r})\n")
    out = tmp_path / "out.nc"
    p = _run(COMMANDS[command] + ["--output", str(out)], tmp_path, [tmp_path / "fake"])
    assert p.returncode == 1, (p.returncode, p.stderr[-2000:])
    assert "Traceback" not in p.stderr and len(p.stderr.strip().splitlines()) == 1, p.stderr[-2000:]
    assert dependency in p.stderr and "libcompiled-7.so.1" in p.stderr and "pip install" in p.stderr
    assert not out.exists() and p.stdout == ""


UNWRITABLE = """\
import errno, os, sys
real = os.replace
def refused(src, dst, *args, **kwargs):  # the output's folder turned read-only after the checks passed
    if os.path.basename(str(dst)) == 'out.nc' and 'rockstudy-kept' not in str(dst):
        raise OSError(errno.EROFS, os.strerror(errno.EROFS))
    return real(src, dst, *args, **kwargs)
os.replace = refused
from rockstudy.cli import main
sys.exit(main(sys.argv[1:]))
"""


@pytest.mark.parametrize("command", ["spectrum", "simulate"])
def test_an_output_that_cannot_be_written_is_one_line_and_the_result_is_kept(command, tmp_path):
    import xarray as xr

    out = tmp_path / "results" / "out.nc"
    p = _run(COMMANDS[command] + ["--output", str(out)], tmp_path, code=UNWRITABLE)
    kept = tmp_path / "tmp" / "rockstudy-kept" / "out.nc"
    assert p.returncode == 2, (p.returncode, p.stderr[-2000:])
    errors = [line for line in p.stderr.splitlines() if not line[:4].isdigit()]  # not the progress log's lines
    assert "Traceback" not in p.stderr and len(errors) == 1, p.stderr[-2000:]
    assert str(out) in p.stderr and "Read-only file system" in p.stderr and str(kept) in p.stderr
    assert not out.exists() and not list(out.parent.glob(".*part"))
    with xr.open_dataset(kept) as ds:  # the computed result, whole
        assert ("threshold" if command == "spectrum" else "theta") in ds
