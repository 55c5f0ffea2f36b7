"""The validation layer: limits, paths, physical meaning, atomic writes, and property-based
tests over CLI arguments and config values (hypothesis).

Set ``ROCKSTUDY_HYPOTHESIS_EXAMPLES`` to run a longer sweep than the CI default.
"""
import copy
import functools
import importlib
import json
import math
import os
import time
import tracemalloc
from pathlib import Path

import jsonschema
import numpy as np
import pytest
import xarray as xr
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rockstudy import cli
from rockstudy.core import io
from rockstudy.core import validation as v
from rockstudy.model.block import BLOCK_PRESETS, Block
from rockstudy.model.excitation import check_time_span, excitation_duration
from rockstudy.studies import datasets, parameters, study

ROOT = Path(__file__).resolve().parents[2]
TINY = yaml.safe_load((ROOT / ".test" / "config.yaml").read_text())
SCHEMA = yaml.safe_load((ROOT / "workflow" / "schemas" / "config.schema.yaml").read_text())
EXAMPLES = int(os.environ.get("ROCKSTUDY_HYPOTHESIS_EXAMPLES", "60"))
PROPERTY = settings(max_examples=EXAMPLES, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])


# --- the checks themselves -------------------------------------------------------------------
@pytest.mark.parametrize("value", [float("nan"), float("inf"), -float("inf"), "1", None, True])
def test_check_number_refuses_non_numbers_and_non_finite(value):
    with pytest.raises(v.InputError, match="free_time"):
        v.check_nonnegative("free_time", value, "s")


def test_check_range_message_names_value_unit_and_limit():
    with pytest.raises(v.InputError) as exc:
        v.check_nonnegative("--free-time", 1e9, "s", v.MAX_FREE_TIME)
    assert str(exc.value) == "--free-time = 1e+09 s is not allowed: allowed is 0 <= --free-time <= 3600 s"


@pytest.mark.parametrize("value,ok", [(0, True), (2**63 - 1, True), (2**63, False), (-1, False), (1.5, False),
                                      (1e3, True), (True, False)])
def test_integers_must_fit_a_netcdf_int64(value, ok):
    if ok:
        assert v.check_int_range("seed", value) == int(value)
    else:
        with pytest.raises(v.InputError, match="seed"):
            v.check_int_range("seed", value)


def test_grid_size_is_counted_without_building_the_grid():
    assert v.grid_size(0.25, 5.0, 0.1) == len(parameters.frequency_ratios({"start": 0.25, "stop": 5.0, "step": 0.1}))
    t0 = time.perf_counter()
    with pytest.raises(v.InputError, match=r"frequency_grid.step = 1e-12 .* 4750000000001 points"):
        v.check_grid("frequency_grid", 0.25, 5.0, 1e-12, high=v.MAX_FREQUENCY_RATIO)
    assert time.perf_counter() - t0 < 0.1


def test_bisection_steps_hand_worked():
    assert v.bisection_steps(0.1, 0.01) == 4  # 0.1 / 2^4 = 0.00625 <= 0.01 < 0.0125
    assert v.bisection_steps(0.1, 0.1) == 0
    assert v.check_amplitude_grid(0.9, 6.0, 0.1, 0.01) == 52 + 4


def test_resolution_below_floating_point_is_refused():
    with pytest.raises(v.InputError, match="amplitude_grid.resolution"):
        v.check_amplitude_grid(0.9, 6.0, 0.1, 1e-20)


def test_time_span_steps_and_controller_samples(blc06):
    check_time_span(blc06, "modulated", [0.25, 5.0], 30.0, 0.01)
    with pytest.raises(v.InputError, match=r"frequency_ratio = 1e-05 .* the limit is 3600 s"):
        check_time_span(blc06, "modulated", [1e-5], 30.0)
    with pytest.raises(v.InputError, match="sampling_time = 1e-09 s"):
        check_time_span(blc06, "modulated", [2.0], 30.0, 1e-9)
    tiny = Block(width=1e-4, height=4e-4, depth=1e-4)  # the smallest block: p ~ 190 rad/s
    check_time_span(tiny, "modulated", [100.0], 30.0)
    with pytest.raises(v.InputError, match="steps"):  # at omega_p/p = 1000, steps of ~2 us over 30 s
        check_time_span(tiny, "modulated", [1000.0], 30.0)


def test_housner_restitution_needs_a_slender_block():
    with pytest.raises(ValueError, match=r"e = 1 - 1.5 sin\^2\(alpha\) = -0.412 < 0"):
        Block(width=1.6, height=0.4, depth=1.0)
    squat = Block(width=1.6, height=0.4, depth=1.0, restitution=0.5)  # an explicit e is the user's choice
    assert squat.e == 0.5
    assert Block(width=2.0, height=2.0 / math.sqrt(2), depth=1.0).e == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("path,needle", [("/proc/x.nc", "system folder"), ("/sys/x.nc", "system folder"),
                                         ("/etc/passwd/x.nc", "cannot create"), ("", "give a file name")])
def test_output_paths_are_checked(path, needle):
    with pytest.raises(v.InputError, match=needle):
        v.check_output_path("--output", path)


def _special(kind: str, folder: Path) -> Path:
    """An existing file that is not a regular one, outside /dev."""
    import socket
    import stat
    path = folder / kind
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "socket":
        sock = socket.socket(socket.AF_UNIX)
        sock.bind(str(path))
        sock.close()
    elif kind == "link-to-fifo":
        os.mkfifo(folder / "target")
        path.symlink_to(folder / "target")
    else:
        try:
            os.mknod(path, 0o600 | stat.S_IFCHR, os.makedev(1, 3))  # the null device, made outside /dev
        except PermissionError:
            pytest.skip("making a device node needs root")
    return path


@pytest.mark.parametrize("kind", ["fifo", "socket", "link-to-fifo", "device"])
def test_output_path_refuses_an_existing_non_regular_file_anywhere(kind):
    import stat
    import tempfile
    folder = Path(tempfile.mkdtemp(prefix="rs-", dir="/tmp"))  # short: a socket's path has at most 107 bytes
    try:
        path = _special(kind, folder)
        before = os.lstat(path).st_mode
        with pytest.raises(v.InputError, match="not a regular file") as refused:
            v.check_output_path("--output", path)
        assert str(path) in str(refused.value) and len(str(refused.value).splitlines()) == 1
        assert os.lstat(path).st_mode == before and not stat.S_ISREG(os.stat(path).st_mode)  # still there
        assert sorted(p.name for p in folder.iterdir()) == sorted({path.name, "target"} & {
            p.name for p in folder.iterdir()})  # no probe or other file left behind
        regular = folder / "x.nc"
        regular.write_text("")
        assert v.check_output_path("--output", regular) == regular  # a regular file is replaced as before
    finally:
        for p in folder.iterdir():
            p.unlink()
        folder.rmdir()


def test_output_path_folder_and_format(tmp_path):
    with pytest.raises(v.InputError, match="is a folder"):
        v.check_output_path("--output", tmp_path)
    with pytest.raises(v.InputError, match=r"\.png"):
        v.check_output_path("--plot", tmp_path / "x.jpg2", formats=v.FIGURE_FORMATS)
    assert v.check_output_path("--output", tmp_path / "new" / "x.nc") == tmp_path / "new" / "x.nc"
    assert not (tmp_path / "new").exists()  # the check makes no folder (the writer does, after every check)
    assert [p.name for p in tmp_path.iterdir()] == []  # and the probe file is removed


def test_a_max0_rule_in_g_and_ratios(blc06):
    assert v.check_a_max0("a_max0", 1.0, blc06.alpha, 4.5) == pytest.approx(4.0)
    with pytest.raises(v.InputError, match=r"a_max0 = 1.2 g .* 4.8 as an amplitude ratio .* <= 1.125 g"):
        v.check_a_max0("a_max0", 1.2, blc06.alpha, 4.5)


# --- the config check ----------------------------------------------------------------------------
def config_error(config):
    """None when the schema and check_study accept ``config``, else the message."""
    try:
        jsonschema.validate(config, SCHEMA)
        study.check_study(config)
    except jsonschema.ValidationError as exc:
        return f"{'.'.join(map(str, exc.absolute_path))}: {exc.message}"
    except ValueError as exc:
        return str(exc)
    return None


@pytest.mark.parametrize("change,key", [
    (lambda c: c.update(free_time=float("nan")), "free_time"),
    (lambda c: c.update(seed=2**70), "seed"),
    (lambda c: c.update(block={"width": 1.6, "height": 0.4, "depth": 1.0}), "block.restitution"),
    (lambda c: c["frequency_grid"].update(step=1e-9), "frequency_grid.step"),
    (lambda c: c["amplitude_grid"].update(resolution=1e-20), "amplitude_grid.resolution"),
    (lambda c: c.update(a_max0=1.2), "a_max0"),
    (lambda c: c["anchorage"].update(kappa_max=float("inf")), "anchorage.kappa_max"),
    (lambda c: c.update(realisations=100_000, realisations_per_job=100_000), "realisations_per_job"),
    (lambda c: c["sampling_sweep"].update(sampling_times=[1e-7]), "sampling_sweep.sampling_times[0]"),
    (lambda c: c.update(noise_reference_frequency_ratio=1e-12), "noise_reference_frequency_ratio"),
    (lambda c: c.update(block={"width": 1e12, "height": 4e12, "depth": 1.0}), "block.width"),
])
def test_config_check_names_the_key(change, key):
    config = copy.deepcopy(TINY)
    change(config)
    message = config_error(config)
    assert message is not None and key in message, message


def test_tiny_and_default_configs_pass():
    assert config_error(copy.deepcopy(TINY)) is None
    assert config_error(yaml.safe_load((ROOT / "config.yaml").read_text())) is None


# --- property-based: config values ---------------------------------------------------------------
NUMERIC_KEYS = [("free_time",), ("seed",), ("realisations",), ("realisations_per_job",), ("a_max0",),
                ("noise_records_stored",), ("noise_reference_frequency_ratio",),
                ("frequency_grid", "start"), ("frequency_grid", "stop"), ("frequency_grid", "step"),
                ("amplitude_grid", "start"), ("amplitude_grid", "stop"), ("amplitude_grid", "step"),
                ("amplitude_grid", "resolution"), ("anchorage", "kappa_max"), ("anchorage", "kappa_min"),
                ("anchorage", "damping_ratio"), ("delay_sweep", "sampling_time"),
                ("control_histories", "frequency_ratio"), ("example_point", "amplitude_ratio"),
                ("noise_levels", "R005")]
ANY_NUMBER = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-2**80, 2**80),
                       st.sampled_from([0, 1, -1, 1e-300, 1e300, 2**63 - 1, 2**63, 0.5, 1e-9]))


@PROPERTY
@given(changes=st.lists(st.tuples(st.sampled_from(NUMERIC_KEYS), ANY_NUMBER), min_size=1, max_size=3))
def test_property_config_is_refused_naming_a_key_or_its_work_is_bounded(changes):
    config = copy.deepcopy(TINY)
    for path, value in changes:
        node = config
        for k in path[:-1]:
            node = node[k]
        node[path[-1]] = value
    t0 = time.perf_counter()
    message = config_error(config)
    assert time.perf_counter() - t0 < 5.0
    if message is None:  # accepted: what it implies is within the limits
        fg, ag = config["frequency_grid"], config["amplitude_grid"]
        n_freq = v.grid_size(fg["start"], fg["stop"], fg["step"])
        assert n_freq <= v.MAX_GRID_POINTS
        per_job = min(config["realisations_per_job"], config["realisations"])
        assert per_job * n_freq * v.check_amplitude_grid(**ag) <= v.MAX_SIMULATIONS
        for path, _ in changes:  # the value each changed key ended with (a later change may overwrite)
            node = config
            for k in path:
                node = node[k]
            assert math.isfinite(float(node)), path
        p = BLOCK_PRESETS["BLC06"].p
        for f in (fg["start"], config["noise_reference_frequency_ratio"],
                  config["control_histories"]["frequency_ratio"]):
            assert excitation_duration(config["excitation"], f * p) + config["free_time"] <= v.MAX_TIME_SPAN
    else:  # refused: the message names one of the keys that were changed (or one they constrain)
        names = {p[-1] for p, _ in changes} | {".".join(p) for p, _ in changes}
        related = {"stop", "start", "step", "resolution", "a_max0", "realisations", "realisations_per_job",
                   "kappa_min", "kappa_max", "noise_levels", "sampling_times[0]", "frequency_ratio"}
        assert any(n in message for n in names | related), (changes, message)


# --- property-based: CLI arguments ---------------------------------------------------------------
OPTION_VALUES = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(-2**70, 2**70).map(str),
    st.sampled_from(["nan", "inf", "-1", "0", "1e-12", "1e15", "1e300", "abc", "", "2", "0.5", "1e3"]))
SPECTRUM_OPTIONS = ["--frequency-start", "--frequency-stop", "--frequency-step", "--realisations", "--threads",
                    "--min-amplitude-ratio", "--max-amplitude-ratio", "--amplitude-step", "--resolution",
                    "--noise-level", "--free-time", "--sampling-time", "--delay", "--kappa-max", "--kappa-min",
                    "--damping-ratio", "--seed", "--realisation"]


class Reached(Exception):
    """The command got past its checks to the heavy work."""


@pytest.fixture
def no_heavy_work(monkeypatch):
    """Replace the spectrum computation by a stub: checks run for real, the work does not."""
    import rockstudy.analysis.spectra as spectra

    def stub(*args, **kwargs):
        raise Reached
    monkeypatch.setattr(spectra, "spectrum", stub)


def error_line(err: str) -> str:
    """The "rockstudy: error: ..." line (the usage line above it names every option)."""
    return next((line for line in err.splitlines() if line.startswith("rockstudy: error:")), "")


def run_cli(argv):
    """(exit status, stderr-like message) of ``rockstudy argv`` in this process."""
    try:
        cli.main(argv)
    except SystemExit as exc:
        return exc.code, None
    except Reached:
        return "reached", None
    return 0, None


@PROPERTY
@given(options=st.lists(st.tuples(st.sampled_from(SPECTRUM_OPTIONS), OPTION_VALUES), min_size=1, max_size=4,
                        unique_by=lambda t: t[0]))
def test_property_spectrum_arguments_refused_or_bounded(options, tmp_path_factory, no_heavy_work, capsys):
    out = tmp_path_factory.mktemp("spec") / "s.nc"
    argv = ["spectrum", "--output", str(out)] + [x for opt, val in options for x in (opt, val)]
    tracemalloc.start()
    t0 = time.perf_counter()
    status, _ = run_cli(argv)
    elapsed = time.perf_counter() - t0
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    err = capsys.readouterr().err
    assert elapsed < 5.0 and peak < 200 * 2**20, (argv, elapsed, peak)
    assert not out.exists() and list(out.parent.iterdir()) == []  # never a partial output
    if status == 2:
        assert any(opt in error_line(err) for opt, _ in options), (argv, err)
    else:
        assert status == "reached", (argv, status, err)


SIM_OPTIONS = st.fixed_dictionaries({
    "--frequency-ratio": st.one_of(st.floats(0.3, 8.0), st.sampled_from(["0", "-1", "nan", "1e-6", "2e3"])),
    "--amplitude-ratio": st.one_of(st.floats(0.5, 50.0), st.sampled_from(["0", "inf", "1e4"])),
    "--noise-level": st.one_of(st.sampled_from(["0", "0.05", "0.2"]), st.sampled_from(["1", "-0.1", "nan"])),
    "--sampling-time": st.sampled_from(["0", "0.01", "0.1", "1e-9", "-1"]),
    "--kappa-max": st.one_of(st.floats(0.0, 5.0), st.sampled_from(["1e5", "nan"])),
    "--free-time": st.one_of(st.floats(0.0, 5.0), st.sampled_from(["1e9", "-1"])),
    "--realisation": st.sampled_from(["0", "3", "-1", str(2**63), "1.5"]),
    "--strategy": st.sampled_from(["FS", "PASSIVE", "CS01", "CS02", "CS03"]),
})


@functools.lru_cache(maxsize=None)
def _engine_ready() -> bool:
    """Compile (or load from numba's cache) the engine once, so that the time limit of the property below
    bounds the command's own work, not a compile slowed down by a busy machine."""
    run_cli(["simulate", "--frequency-ratio", "2", "--amplitude-ratio", "1.0"])
    return True


@PROPERTY
@given(options=SIM_OPTIONS, with_output=st.booleans())
def test_property_simulate_exits_0_with_a_valid_result_or_2_naming_an_input(options, with_output, tmp_path_factory,
                                                                           capsys):
    _engine_ready()
    capsys.readouterr()
    out = tmp_path_factory.mktemp("sim") / "h.nc"
    argv = ["simulate"] + [x for opt, val in options.items() for x in (opt, str(val))]
    if with_output:
        argv += ["--output", str(out)]
    t0 = time.perf_counter()
    status, _ = run_cli(argv)
    elapsed = time.perf_counter() - t0
    captured = capsys.readouterr()
    assert elapsed < 60.0, (argv, elapsed)
    if status == 2:
        assert any(opt in error_line(captured.err) for opt in options), (argv, captured.err)
        assert not out.exists()
    else:
        assert status == 0, (argv, captured.err)
        result = json.loads(captured.out)
        assert result["status"] in ("rest", "overturned", "time limit", "undetermined")
        if with_output and result["status"] != "undetermined":
            with xr.open_dataset(out) as ds:  # complete and readable
                assert ds.attrs["frequency_ratio"] == float(options["--frequency-ratio"])
    assert [p.name for p in out.parent.iterdir()] in ([], ["h.nc"])


# --- CLI results that say what they mean -----------------------------------------------------------
def test_threshold_reports_the_scan_start_and_unchecked_amplitudes(capsys):
    assert cli.main(["threshold", "--strategy", "FS", "--frequency-ratio", "2", "--min-amplitude-ratio", "3",
                     "--max-amplitude-ratio", "4.5", "--amplitude-step", "0.3", "--resolution", "0.05"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["scan_start_amplitude_ratio"] == 3.0 and out["lower_amplitudes_checked"] is False
    assert "were not scanned" in out["note"]
    uplift = 1 / __import__("rockstudy.model.excitation", fromlist=["x"]).modulated_peak()
    assert out["uplift_amplitude_ratio"] == pytest.approx(uplift)
    cli.main(["threshold", "--strategy", "FS", "--frequency-ratio", "2", "--max-amplitude-ratio", "1.5"])
    out = json.loads(capsys.readouterr().out)
    assert out["lower_amplitudes_checked"] is True and "note" not in out


def test_simulate_event_cap_is_an_undetermined_result(monkeypatch, capsys):
    # the CLI runs a scenario through rockstudy.analysis.scenario, which calls the engine's simulate
    scenario = importlib.import_module("rockstudy.analysis.scenario")

    def capped(*args, **kwargs):
        raise RuntimeError("the fast engine hit its cap of 2000000 events at t = 1 s")
    monkeypatch.setattr(scenario, "simulate", capped)
    assert cli.main(["simulate"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["status"] == "undetermined" and "cap" in out["message"]


def test_jos_refuses_a_max0_above_the_scan_and_reports_undefined(tmp_path, capsys):
    block = BLOCK_PRESETS["BLC06"]
    ds = datasets.document_missing(xr.Dataset(
        {"threshold": ("frequency_ratio", [np.nan, np.nan])},
        coords={"frequency_ratio": [1.0, 2.0]},
        attrs={**block.to_attrs(), "grid_amplitude_start": 0.9, "grid_amplitude_stop": 4.5,
               "grid_amplitude_step": 0.6}))
    io.write_netcdf(ds, tmp_path / "a.nc")
    args = ["jos", "--reference", str(tmp_path / "a.nc"), "--system", str(tmp_path / "a.nc")]
    assert cli.main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["J_OS_percent"] is None and out["N_star"] == 0 and "undefined" in out["note"]
    with pytest.raises(SystemExit) as exc:
        cli.main(args + ["--a-max0", "1.2"])
    assert exc.value.code == 2 and "--a-max0 = 1.2 g" in capsys.readouterr().err
