"""Running the study's Snakefile from the tests: the tiny study's config, the snakemake command in a folder,
and a dry run of a given config."""
import subprocess
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
TEST_CONFIG = ROOT / ".test" / "config.yaml"
TINY = ("--configfile", str(TEST_CONFIG), "--replace-workflow-config")


def command(*args, workdir) -> list:
    """The ``snakemake`` command line on the project's Snakefile with ``workdir`` as its working folder."""
    return ["snakemake", "--snakefile", str(ROOT / "Snakefile"), "--directory", str(workdir), *args]


def snakemake(*args, workdir):
    """:func:`command` run to its end; the finished run (output captured)."""
    return subprocess.run(command(*args, workdir=workdir), capture_output=True, text=True, timeout=1800)


def dry_run(config: dict, workdir, *args):
    """A dry run (``-n``) of ``config`` (written to ``workdir/config.yaml``, replacing config.yaml's)."""
    path = Path(workdir) / "config.yaml"
    path.write_text(yaml.safe_dump(config))
    return snakemake("-n", "--configfile", str(path), "--replace-workflow-config", *args, workdir=workdir)
