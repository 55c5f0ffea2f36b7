"""Overlays replace the sections they give: a `--configfile`, then Snakemake's `--config KEY=VALUE` (applied
last, as Snakemake applies it, with its values typed as in a file), and the CLI's options over
`rockstudy --config FILE`. The workflow cases read what a dry run's jobs are given from their params."""
import json
import re
import shutil
import subprocess

import pytest
import yaml

from rockstudy.core import config_files
from rockstudy.core.validation import InputError
from workflow_runs import ROOT, TEST_CONFIG

needs_snakemake = pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake is not installed")

TALL = {"width": 0.5, "height": 2.5, "depth": 0.5}
TALL_WORD = "block={width: 0.5, height: 2.5, depth: 0.5}"
WRAPPER = f"""import json
include: {str(ROOT / "Snakefile")!r}
print("PLANNED " + json.dumps({{"block": rules.compile_engine.params.scenario["block"], "noise_levels": LEVELS}}))
"""
"""A Snakefile that includes the study's and prints what its jobs are given: the block of a job's scenario
(params of rule compile_engine) and the noise levels the rules expand."""


def dry_run(workdir, *args, config=None):
    """A dry run of the study (target ``all``) through :data:`WRAPPER`, with ``config`` (default: the
    study's config.yaml) as the workflow's ``config.yaml`` and ``args``; the finished run and what its jobs
    are given ({"block", "noise_levels"}, None when the run stopped before)."""
    (workdir / "config.yaml").write_text(yaml.safe_dump(config) if config else (ROOT / "config.yaml").read_text())
    (workdir / "Snakefile").write_text(WRAPPER)
    res = subprocess.run(["snakemake", "--snakefile", str(workdir / "Snakefile"), "--directory", str(workdir), "-n",
                          *args, "--", "all"], capture_output=True, text=True, timeout=600)
    lines = [line for line in res.stdout.splitlines() if line.startswith("PLANNED ")]
    return res, (json.loads(lines[0].split(" ", 1)[1]) if lines else None)


def job_counts(stdout: str) -> dict:
    """Jobs per rule in a dry run's "Job stats" table."""
    table = stdout.split("Job stats:", 1)[1].split("\n\n", 1)[0]
    return {m.group(1): int(m.group(2)) for m in re.finditer(r"^(\w+)\s+(\d+)$", table, flags=re.MULTILINE)}


@needs_snakemake
def test_command_line_block_replaces_the_preset(tmp_path):
    """`--config block={width..}` over config.yaml's `block: {preset: BLC06}`: the jobs get the dimensions
    as numbers (Snakemake alone merges them into the preset, as strings, and the block is refused)."""
    assert yaml.safe_load((ROOT / "config.yaml").read_text())["block"] == {"preset": "BLC06"}
    res, given = dry_run(tmp_path, "--config", TALL_WORD, "results_dir=out")
    assert res.returncode == 0, res.stderr[-2000:]
    assert given["block"] == TALL


@needs_snakemake
def test_command_line_noise_levels_replace_the_levels(tmp_path):
    """`--config noise_levels={...}` replaces config.yaml's four levels: two levels, two noise jobs and a
    spectrum per level and strategy (one job per strategy), none of the levels left out."""
    config = yaml.safe_load((ROOT / "config.yaml").read_text())
    assert set(config["noise_levels"]) > {"R000", "R005"}
    res, given = dry_run(tmp_path, "--config", "noise_levels={R000: 0.0, R005: 0.05}", "results_dir=out")
    assert res.returncode == 0, res.stderr[-2000:]
    assert given["noise_levels"] == {"R000": 0.0, "R005": 0.05}
    jobs = job_counts(res.stdout)
    assert jobs["noise"] == 2 and jobs["spectrum"] == len(config["strategies"])
    for strategy in config["strategies"]:
        assert f"out/spectra/{strategy}_R000.nc, out/spectra/{strategy}_R005.nc\n" in res.stdout
    for level in set(config["noise_levels"]) - {"R000", "R005"}:
        assert f"out/noise/{level}.nc" not in res.stdout


@needs_snakemake
@pytest.mark.parametrize("file_block, word, expected", [
    ({"preset": "BLC06"}, TALL_WORD, TALL),
    (TALL, "block={preset: BLC06}", {"preset": "BLC06"}),
])
def test_command_line_comes_after_the_config_files(tmp_path, file_block, word, expected):
    """A `--configfile` sets the block and the noise levels, `--config` sets them again: the command line's
    are the ones the jobs get (Snakemake applies --config last), whole."""
    tiny = yaml.safe_load(TEST_CONFIG.read_text())
    overlay = tmp_path / "mine.yaml"
    overlay.write_text(yaml.safe_dump({**tiny, "block": file_block, "a_max0": 0.5}))
    res, given = dry_run(tmp_path, "--configfile", str(overlay), "--replace-workflow-config",
                         "--config", word, "noise_levels={R000: 0.0, R005: 0.07}", "results_dir=out")
    assert res.returncode == 0, res.stderr[-2000:]
    assert given == {"block": expected, "noise_levels": {"R000": 0.0, "R005": 0.07}}


@needs_snakemake
def test_a_command_line_block_is_not_merged_into_the_preset(tmp_path):
    """`--config block={height: 2.0}` replaces the block too: a block without width and depth is refused,
    naming it, instead of becoming BLC06 with another height."""
    res, given = dry_run(tmp_path, "--config", "block={height: 2.0}", "results_dir=out")
    assert res.returncode != 0 and given is None
    assert "config error: block" in res.stderr and "Traceback" not in res.stderr


def snakemake_parse(words):
    """The command line's config as Snakemake 9 parses ``--config`` (``snakemake.cli.parse_config``)."""
    cli = pytest.importorskip("snakemake.cli")
    return cli.parse_config(words)


def test_command_line_values_are_typed_as_in_a_file():
    words = [TALL_WORD, "results_dir=out", "seed=5", "anchorage={kappa_max: 2.0}", "strategies=[FS, CS01]",
             "noise_levels={R000: 0.0, R005: 0.05}"]
    parsed = snakemake_parse(words)
    assert parsed["block"]["width"] == "0.5"  # Snakemake alone: a string in a mapping
    overlay = config_files.command_line_overlay(parsed, words)
    assert overlay == {"block": TALL, "results_dir": "out", "seed": 5, "anchorage": {"kappa_max": 2.0},
                       "strategies": ["FS", "CS01"], "noise_levels": {"R000": 0.0, "R005": 0.05}}
    twice = ["block={width: 0.5}", "block={height: 2.5}"]  # a key given twice is merged, as Snakemake merges it
    assert config_files.command_line_overlay(snakemake_parse(twice), twice) == {"block": {"width": 0.5,
                                                                                          "height": 2.5}}
    assert config_files.command_line_overlay({"seed": 5}) == {"seed": 5}  # no words: taken as given


def test_command_line_alias_bomb_is_refused_before_any_walk():
    """A list of lists of aliases, 10^5 values and more once expanded, in a few hundred bytes."""
    text, previous = "&a0 [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]", "a0"
    for depth in range(1, 6):
        text, previous = f"&a{depth} [{text}, " + ", ".join([f"*{previous}"] * 9) + "]", f"a{depth}"
    assert len(text) < 500
    with pytest.raises(InputError, match="--config strategies"):
        config_files.command_line_overlay({"strategies": ["x"]}, [f"strategies={text}"])


def test_apply_command_line_merges_and_replaces():
    """Applied to a config Snakemake made: its values merged in (the other anchorage keys stay), the block
    and the noise levels replaced whole."""
    config = {"block": {"preset": "BLC06", "width": "0.5"}, "anchorage": {"kappa_max": "2.0", "kappa_min": 0.0},
              "noise_levels": {"R000": 0.0, "R001": 0.01, "R005": "0.05"}}
    overlay = {"block": {"width": 0.5}, "anchorage": {"kappa_max": 2.0}, "noise_levels": {"R005": 0.05}}
    assert config_files.apply_command_line(config, overlay) == {
        "block": {"width": 0.5}, "anchorage": {"kappa_max": 2.0, "kappa_min": 0.0}, "noise_levels": {"R005": 0.05}}
    config = {"reproduction": {"strategy": "FS", "readings": {"a": {"step": 0.0025}, "b": {"step": "0.005"}}}}
    overlay = {"reproduction": {"readings": {"b": {"step": 0.005}}}}  # a section inside a section
    assert config_files.apply_command_line(config, overlay) == {
        "reproduction": {"strategy": "FS", "readings": {"b": {"step": 0.005}}}}


# rockstudy --config FILE: the block given on the command line replaces the file's, whole.

def scenario_of(argv):
    from rockstudy.cli import _apply_config, _scenario, build_parser
    parser = build_parser()
    args = parser.parse_args(argv)
    _apply_config(args, argv, parser)
    return _scenario(args, parser)


def _config_file(tmp_path, block):
    path = tmp_path / "study.yaml"
    path.write_text(yaml.safe_dump({**yaml.safe_load(TEST_CONFIG.read_text()), "block": block}))
    return str(path)


def test_cli_dimensions_replace_the_files_preset(tmp_path):
    block = scenario_of(["simulate", "--config", _config_file(tmp_path, {"preset": "BLC06"}),
                         "--width", "0.5", "--height", "2.5", "--depth", "0.5"]).block
    assert (block.width, block.height, block.depth) == (0.5, 2.5, 0.5)
    assert scenario_of(["simulate", "--config", _config_file(tmp_path, TALL)]).block.height == 2.5


def test_cli_block_options_are_not_merged_into_the_files_block(tmp_path, capsys):
    """One dimension on the command line does not change the file's block: it replaces it, and a block
    without width and depth is refused naming the options."""
    from rockstudy.cli import main
    with pytest.raises(SystemExit) as stop:
        main(["simulate", "--config", _config_file(tmp_path, TALL), "--height", "3.0"])
    err = capsys.readouterr().err
    assert stop.value.code == 2 and "width" in err and "depth" in err and len(err.strip().splitlines()) <= 3


# Numbers as written: `010` is octal 8 in a config file (YAML 1.1) and 10 on Snakemake's command line; both
# paths refuse it before any job, naming the key and both readings.
@needs_snakemake
@pytest.mark.parametrize("how,key", [
    (("--config", "free_time=010"), "--config free_time"),
    (("--config", "block={width: 010, height: 2.5, depth: 0.5}"), "--config block.width"),
    ("file", "line 1: free_time"),
])
def test_a_number_not_read_as_written_is_refused_on_both_paths(tmp_path, how, key):
    if how == "file":
        overlay = tmp_path / "overlay.yaml"
        overlay.write_text("free_time: 010\n")
        how = ("--configfile", str(overlay))
    res, given = dry_run(tmp_path, *how, "results_dir=out" if how[0] == "--config" else "--config",
                         *(() if how[0] == "--config" else ("results_dir=out",)))
    assert res.returncode == 1 and given is None, res.stdout[-2000:]
    errors = [line for line in res.stderr.splitlines() if "error" in line.lower()]
    assert len(errors) == 1 and errors[0].startswith("config error: "), res.stderr
    assert key in errors[0] and "010 is not allowed" in errors[0] and "write 10 or 8" in errors[0], errors[0]
    assert "Job stats" not in res.stdout and not (tmp_path / "out").exists()


@needs_snakemake
def test_the_decimal_on_the_command_line_is_read_as_written(tmp_path):
    wrapper = WRAPPER.replace('"noise_levels": LEVELS', '"noise_levels": LEVELS, "free_time": config["free_time"]')
    (tmp_path / "config.yaml").write_text((ROOT / "config.yaml").read_text())
    (tmp_path / "Snakefile").write_text(wrapper)
    res = subprocess.run(["snakemake", "--snakefile", str(tmp_path / "Snakefile"), "--directory", str(tmp_path),
                          "-n", "--config", "free_time=10", "results_dir=out", "--", "all"],
                         capture_output=True, text=True, timeout=600)
    planned = [line for line in res.stdout.splitlines() if line.startswith("PLANNED ")]
    assert res.returncode == 0 and planned, res.stderr[-2000:]
    assert json.loads(planned[0].split(" ", 1)[1])["free_time"] == 10
