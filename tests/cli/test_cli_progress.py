"""The progress bar at a terminal (``rockstudy spectrum``), and the log lines everywhere else."""
import io
import logging
import subprocess
import sys

import numpy as np

from rockstudy import Control
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, spectrum
from rockstudy.cli.progress import at_terminal, progress_bar

GRID = AmplitudeGrid(stop=2.5, step=0.3, resolution=0.05)


def test_progress_reaches_every_case_and_leaves_the_numbers_alone(blc06, caplog):
    calls = []
    scenario = Scenario(blc06, control=Control("CS01"))
    freqs = np.arange(1.0, 3.01, 0.25)
    with caplog.at_level(logging.INFO, logger="rockstudy"):
        logged = spectrum(scenario, freqs, grid=GRID)
    assert sum("cases (" in r.getMessage() for r in caplog.records) > 0
    caplog.clear()
    with caplog.at_level(logging.INFO, logger="rockstudy"):
        barred = spectrum(scenario, freqs, grid=GRID, progress=lambda *a: calls.append(a))
    assert not any("cases (" in r.getMessage() for r in caplog.records)  # the bar instead of the log lines
    done = [c[0] for c in calls]
    assert done[0] == 0 and done[-1] == len(freqs) and done == sorted(done) and len(done) == len(freqs) + 1
    assert {c[1] for c in calls} == {len(freqs)}
    np.testing.assert_array_equal(barred.threshold.values, logged.threshold.values)


def test_bar_drawn_at_a_terminal_only():
    assert not at_terminal(io.StringIO())
    with progress_bar(file=io.StringIO()) as update:
        assert update is None  # not a terminal: the log lines
    out = io.StringIO()
    with progress_bar(enabled=True, file=out) as update:
        update(0, 8, "spectrum FS")
        update(8, 8, "spectrum FS")
    assert "spectrum FS" in out.getvalue() and "8/8" in out.getvalue()


def test_spectrum_into_a_pipe_logs_lines_and_no_bar(tmp_path):
    p = subprocess.run([sys.executable, "-m", "rockstudy.cli", "spectrum", "--strategy", "FS", "--frequency-start",
                        "1", "--frequency-stop", "2", "--max-amplitude-ratio", "2", "--output",
                        str(tmp_path / "s.nc")], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    assert "cases (100%)" in p.stderr and "\x1b[" not in p.stderr
