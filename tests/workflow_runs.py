"""Running the study's Snakefile from the tests: the tiny study's config and a snakemake call in a folder."""
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TEST_CONFIG = ROOT / ".test" / "config.yaml"
TINY = ("--configfile", str(TEST_CONFIG), "--replace-workflow-config")


def snakemake(*args, workdir):
    """``snakemake`` on the project's Snakefile with ``workdir`` as its working folder; the finished run."""
    cmd = ["snakemake", "--snakefile", str(ROOT / "Snakefile"), "--directory", str(workdir), *args]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=1800)
