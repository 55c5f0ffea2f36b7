"""Ctrl-C of a running command: `rockstudy spectrum` stopped by SIGINT in the middle of its simulations exits
with status 130 and one line, no traceback, and leaves nothing at `--output`."""
import os
import queue
import signal
import subprocess
import sys
import threading
import time

import rockstudy

FIRST_PROGRESS_S = 300
"""Longest wait for the first progress line: numba compiles the engine on the first run in a fresh checkout
(about a minute; a second or two once its cache is filled)."""
EXIT_AFTER_SIGINT_S = 30
"""Longest wait for the exit after SIGINT: the spectrum checks for it between progress chunks (about 1.5 s
each here), and finishes in about 15 s if it never does."""


def _lines(stream, into: queue.Queue) -> None:
    for line in stream:
        into.put(line)
    into.put(None)


def _interrupt(argv):
    """Start ``argv``, send SIGINT after its first progress line; (exit status, stderr lines before the signal,
    stderr lines after it, stdout)."""
    environ = dict(os.environ)
    environ["PYTHONPATH"] = os.pathsep.join([os.path.dirname(os.path.dirname(rockstudy.__file__)),
                                             environ.get("PYTHONPATH", "")])
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=environ,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))  # as from a terminal
    lines: queue.Queue = queue.Queue()
    reader = threading.Thread(target=_lines, args=(proc.stderr, lines), daemon=True)
    reader.start()
    before, deadline = [], time.monotonic() + FIRST_PROGRESS_S
    try:
        while not (before and " cases (" in before[-1]):  # "spectrum ...: 96/960 cases (10%), ..."
            line = lines.get(timeout=max(deadline - time.monotonic(), 0.01))
            assert line is not None, "".join(before)
            before.append(line)
        assert proc.poll() is None, "the spectrum ended before it could be interrupted"
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=EXIT_AFTER_SIGINT_S)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    reader.join(timeout=10)
    after = []
    while not lines.empty():
        line = lines.get()
        if line is not None:
            after.append(line)
    stdout = proc.stdout.read()
    proc.stdout.close()
    proc.stderr.close()
    return proc.returncode, before, after, stdout


def test_sigint_during_a_spectrum_exits_130_quietly_and_writes_nothing(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    # 20 noisy realisations x 48 frequencies: about 15 s of simulations on one core, logged in ten chunks
    argv = [sys.executable, "-m", "rockstudy.cli", "spectrum", "--noise-level", "0.05", "--realisations", "20",
            "--output", str(out / "spectrum.nc")]
    code, before, after, stdout = _interrupt(argv)
    assert code == 130, "".join(before + after)
    assert "Traceback" not in "".join(after) and "KeyboardInterrupt" not in "".join(after), "".join(after)
    assert [line.strip() for line in after if " cases (" not in line] == ["rockstudy: interrupted"], after
    assert len(after) <= 2, after  # at most a progress line that was on its way, and the message
    assert stdout == ""  # the summary line is printed only when the spectrum is written
    assert list(out.iterdir()) == []  # no output, no temporary file beside it


API_SCRIPT = """
import logging, sys
import rockstudy
logging.basicConfig(level=logging.INFO)
scenario = rockstudy.Scenario(rockstudy.BLOCK_PRESETS["BLC06"], noise_level=0.05)
try:
    rockstudy.spectrum(scenario, rockstudy.frequency_grid(), realisations=range(20))
except KeyboardInterrupt:
    print("KeyboardInterrupt")
    sys.exit(3)
except SystemError as exc:
    print("SystemError", exc)
    sys.exit(4)
"""


def test_sigint_during_a_spectrum_of_the_library_raises_keyboard_interrupt():
    """From Python, Ctrl-C in the compiled cases is the KeyboardInterrupt a caller can catch, not a
    SystemError of numba's call back into Python."""
    code, before, after, stdout = _interrupt([sys.executable, "-c", API_SCRIPT])
    assert (code, stdout.strip()) == (3, "KeyboardInterrupt"), "".join(before + after) + stdout
