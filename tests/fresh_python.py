"""Code run in a fresh Python interpreter that imports the rockstudy under test, installed or not."""
import os
import subprocess
import sys

import rockstudy


def run(code: str, **env) -> str:
    """``code`` in a fresh interpreter (this rockstudy on its path; numba's cache folder left to rockstudy
    unless ``NUMBA_CACHE_DIR`` is given in ``env``, the other variables ``env`` sets added); its stdout."""
    environ = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    environ["PYTHONPATH"] = os.pathsep.join([os.path.dirname(os.path.dirname(rockstudy.__file__)),
                                             environ.get("PYTHONPATH", "")])
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env={**environ, **env},
                         timeout=300)
    assert res.returncode == 0, res.stderr
    return res.stdout.strip()
