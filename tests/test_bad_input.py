"""Bad input by class: values generated from the declarations (rockstudy.studies.config_model, through the
schema generated from them) walk the study config check, the command line and the record readers; each case
ends within 2 s in a clear error (at most three lines, naming the input) or in a valid result.

Classes: types (bools, strings, None where a number is declared), ranges (NaN, +-inf, 0, negatives, 1e300,
at and past each declared limit), sizes (lists at and past their limit, grids too fine), config sections
(unknown keys, presets, overlays), records (empty, binary, odd-header, two-way files), units (unknown or
conflicting units), wrong-answer (a file read one way when it could be read two), termination (alias bombs),
faults (a full disk while writing a result) and manners (a closed pipe, --help without the library).

With ROCKSTUDY_BAD_INPUT_COUNTS=<file> every case is recorded (class, passed) in that JSON-lines file
instead of failing the test, so the same cases can be counted against another version of the code.
"""
import copy
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import jsonschema
import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rockstudy.core import config_files, validation
from rockstudy.studies import config_model, study

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = yaml.safe_load((ROOT / "config.yaml").read_text())
SCHEMA_FILE = yaml.safe_load((ROOT / "workflow" / "schemas" / "config.schema.yaml").read_text())
DECLARED = config_model.config_schema()
COUNTS = os.environ.get("ROCKSTUDY_BAD_INPUT_COUNTS")
EXAMPLES = int(os.environ.get("ROCKSTUDY_BAD_INPUT_EXAMPLES", "40"))
PROPERTY = settings(max_examples=EXAMPLES, deadline=None, derandomize=True, database=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
SECONDS = 2.0


def verdict(cls: str, ok: bool, detail: str) -> None:
    """Record a case (counting mode) or assert it."""
    if COUNTS:
        with open(COUNTS, "a") as fh:
            fh.write(json.dumps({"class": cls, "ok": bool(ok), "detail": detail[:300]}) + "\n")
        return
    assert ok, f"[{cls}] {detail}"


def readable(message: str, *names: str) -> bool:
    """At most three lines (of reasonable length), and naming one of ``names``."""
    return (len(message.strip().splitlines()) <= 3 and len(message) < 2000
            and any(name in message for name in names))


# --------------------------------------------------------------------------------------- the study config

def resolve(node):
    while isinstance(node, dict) and "$ref" in node:
        node = DECLARED["$defs"][node["$ref"].rsplit("/", 1)[1]]
    return node


def pick(node, want=None):
    """The alternative of an ``anyOf`` of type ``want`` (else the first that is not null)."""
    node = resolve(node)
    if "anyOf" in node:
        options = [resolve(n) for n in node["anyOf"]]
        return next((n for n in options if n.get("type") == want),
                    next((n for n in options if n.get("type") != "null"), node))
    return node


def declared_at(path, want=None):
    """The declared schema of a config path (keys and list indices), or None."""
    node = resolve(DECLARED)
    for part in path:
        node = resolve(node)
        if "anyOf" in node:
            node = resolve(next((n for n in node["anyOf"] if resolve(n).get("type") != "null"), node))
        if isinstance(part, int):
            node = node.get("items")
        else:
            props = node.get("properties")
            node = props.get(part) if props else node.get("additionalProperties")
        if node is None:
            return None
    return pick(node, want)


def leaves(node, path=()):
    if isinstance(node, dict):
        for k, item in node.items():
            yield from leaves(item, path + (k,))
    elif isinstance(node, list):
        for i, item in enumerate(node):
            yield from leaves(item, path + (i,))
    elif isinstance(node, (int, float)) and not isinstance(node, bool):
        yield path, node


NUMBERS = [p for p, _ in leaves(DEFAULT)]


def key_name(path) -> str:
    out = ""
    for part in path:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def bad_values(decl: dict):
    """(value, must be refused) for a declared number: types, non-finite, the limits and just past them."""
    out = [(True, True), ("1.0", True), (None, True), (float("nan"), True), (float("inf"), True),
           (float("-inf"), True), (1e300, "maximum" in decl or "exclusiveMaximum" in decl), (-1.0, None), (0, None)]
    for key, past in (("minimum", -1), ("exclusiveMinimum", -1), ("maximum", 1), ("exclusiveMaximum", 1)):
        if key in decl:
            limit = decl[key]
            out.append((limit, key.startswith("exclusive")))
            beyond = limit + past * max(abs(limit) * 1e-6, 1e-9)
            if decl.get("type") == "integer":
                beyond = int(limit) + past
            out.append((beyond, True))
    return out


def config_outcome(config):
    """None if the config is accepted, else the message a person reads, the way the Snakefile checks it."""
    try:
        if "config_model" in Path(study.__file__).read_text():  # the declared check first, then the schema
            study.check_study(config)
            jsonschema.validate(config, SCHEMA_FILE)
        else:  # the order before the declarations: sizes, schema (Snakemake prints the error whole), check
            study.check_sizes(config)
            jsonschema.validate(config, SCHEMA_FILE)
            study.check_study(config)
    except jsonschema.ValidationError as exc:
        return str(exc)
    except (ValueError, KeyError, TypeError) as exc:
        return f"{type(exc).__name__}: {exc}" if not isinstance(exc, ValueError) else str(exc)
    return None


config_outcome(copy.deepcopy(DEFAULT))  # the first check imports the model (seconds): not part of any case


def put(config, path, value):
    node = config
    for part in path[:-1]:
        node = node[part]
    node[path[-1]] = value


@PROPERTY
@given(data=st.data())
def test_every_number_of_the_config_by_class(data):
    path = data.draw(st.sampled_from(NUMBERS))
    decl = declared_at(path) or {}
    value, must_refuse = data.draw(st.sampled_from(bad_values(decl)))
    cls = "types" if value is None or isinstance(value, (bool, str)) else "ranges"
    config = copy.deepcopy(DEFAULT)
    put(config, path, value)
    t0 = time.perf_counter()
    message = config_outcome(config)
    took = time.perf_counter() - t0
    name = key_name(path)
    if message is None:
        ok = not must_refuse and took < SECONDS
    else:
        ok = readable(message, name, name.rsplit(".", 1)[-1]) and took < SECONDS
    verdict(cls, ok, f"{name} = {value!r}: {'accepted' if message is None else message[:200]} ({took:.2f} s)")


def list_paths(node, path=()):
    if isinstance(node, dict):
        for k, item in node.items():
            yield from list_paths(item, path + (k,))
    elif isinstance(node, list):
        yield path


LIST_PATHS = list(list_paths(DEFAULT))


@PROPERTY
@given(data=st.data())
def test_every_list_of_the_config_at_and_past_its_size(data):
    path = data.draw(st.sampled_from(LIST_PATHS))
    decl = declared_at(path, "array") or {}
    most = decl.get("maxItems", validation.MAX_LIST_ITEMS)
    length = data.draw(st.sampled_from([0, most + 1, 10 * most + 1, 10**6]))
    config = copy.deepcopy(DEFAULT)
    item = copy.deepcopy(data_at(config, path)[0])
    put(config, path, [item] * length)
    t0 = time.perf_counter()
    message = config_outcome(config)
    took = time.perf_counter() - t0
    name = key_name(path)
    ok = message is not None and readable(message, name) and took < SECONDS
    verdict("sizes", ok, f"{name}: {length} entries -> {'accepted' if message is None else message[:200]} "
                         f"({took:.2f} s)")


def data_at(config, path):
    node = config
    for part in path:
        node = node[part]
    return node


SECTION_CASES = [
    ("typo top", lambda c: c.update(realisatons=3), "realisations"),
    ("typo anchorage", lambda c: c["anchorage"].update(kapa_max=1.0), "kappa_max"),
    ("typo design", lambda c: c["design"].update(stratgies=["FS"]), "strategies"),
    ("typo beyond", lambda c: c["beyond"]["fragility"].update(bootstrp=3), "bootstrap"),
    ("typo reading", lambda c: c["reproduction"]["readings"]["step5ms"].update(stpe=0.01), "step"),
    ("BLC07", lambda c: c["block"].update(preset="BLC07"), "block.preset"),
    ("preset and dimensions", lambda c: c["block"].update(width=0.5), "block"),
    ("design pga levels", lambda c: c["design"]["pga_levels_g"].update(start=1e-300, stop=1e300),
     "design.pga_levels_g"),
    ("design grid", lambda c: c["design"]["blocks"]["amplitude_grid"].update(step=1e-9),
     "design.blocks.amplitude_grid.step"),
    ("design kappa", lambda c: c["design"]["devices"].update(kappa_max=[2e6]), "design.devices.kappa_max"),
    ("design alpha", lambda c: c["design"]["blocks"].update(alpha=[1e-9]), "design.blocks.alpha"),
    ("synthetic dt", lambda c: c["beyond"]["fragility"]["synthetic"].update(dt=True), "beyond.fragility.synthetic.dt"),
    ("record unit", lambda c: c["beyond"]["fragility"].update(records=[{"path": "x.csv", "unit": "kg"}]),
     "records"),
    ("noise level name", lambda c: c["noise_levels"].update({"R 1": 0.1}), "noise_levels"),
]


@pytest.mark.parametrize("label, change, name", SECTION_CASES, ids=[c[0] for c in SECTION_CASES])
def test_config_sections(label, change, name):
    config = copy.deepcopy(DEFAULT)
    change(config)
    t0 = time.perf_counter()
    message = config_outcome(config)
    took = time.perf_counter() - t0
    ok = message is not None and readable(message, name) and took < SECONDS
    verdict("config sections", ok, f"{label}: {'accepted' if message is None else message[:200]}")


def test_an_overlay_block_replaces_the_preset():
    """The README's tall.yaml over config.yaml, merged as Snakemake merges it, then as the Snakefile replaces."""
    overlay = {"results_dir": "results-tall", "block": {"width": 0.5, "height": 2.5, "depth": 0.5}}
    config = copy.deepcopy(DEFAULT)
    config["block"].update(overlay["block"])
    config["results_dir"] = overlay["results_dir"]
    if "replace_sections" in (ROOT / "Snakefile").read_text():  # what the Snakefile does after the merge
        config_files.replace_sections(config, overlay)
    message = config_outcome(config)
    verdict("config sections", message is None, f"tall.yaml overlay: {message}")


def test_an_alias_bomb_is_refused_at_once():
    lines = ["a0: &a0 [1, 2, 3, 4, 5, 6, 7, 8, 9]"]
    lines += [f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, 10)]
    config = copy.deepcopy(DEFAULT)
    config["noise_levels"] = yaml.safe_load("\n".join(lines) + "\n")  # 9^10 values once expanded
    t0 = time.perf_counter()
    message = run_with_alarm(lambda: config_outcome(config), 10)
    took = time.perf_counter() - t0
    verdict("termination", message is not None and took < SECONDS, f"alias bomb: {message!s:.200} ({took:.2f} s)")


def run_with_alarm(fn, seconds):
    import signal

    def stop(*_):
        raise TimeoutError(f"did not end within {seconds} s")
    old = signal.signal(signal.SIGALRM, stop)
    signal.alarm(seconds)
    try:
        return fn()
    except TimeoutError as exc:
        return f"TIMEOUT {exc}\n" * 5
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


# --------------------------------------------------------------------------------------------- records

RECORD_FILES = {
    "empty": ("", None, None, True),
    "binary": (bytes(range(256)) * 40, None, None, True),
    "header only": ("time [s], acceleration [g]\n", None, None, True),
    "three units": ("time [s]; acceleration [m/s^2]; max abs [g]\n0 0.1\n0.01 0.2\n0.02 0.1\n", None, None, True),
    "header vs option": ("time [s], acceleration [g]\n0 0.1\n0.01 0.2\n0.02 0.1\n", "cm/s^2", None, True),
    "two units": ("acceleration [g] [m/s^2]\n0.1\n0.2\n0.1\n", None, 0.01, True),
    "irregular time with dt": ("0 0.1\n0.01 0.2\n0.03 0.1\n0.035 0.3\n", "g", 0.01, True),
    "uniform time with dt": ("0 0.1\n0.01 0.2\n0.02 0.1\n0.03 0.3\n", "g", 0.01, True),
    "irregular time": ("0 0.1\n0.01 0.2\n0.03 0.1\n0.035 0.3\n", "g", None, True),
    "three columns": ("0 0.1 5\n0.01 0.2 5\n0.02 0.1 5\n", "g", None, True),
    "NaN": ("0 0.1\n0.01 nan\n0.02 0.1\n", "g", None, True),
    "unknown unit": ("0 0.1\n0.01 0.2\n0.02 0.1\n", "kg", None, True),
    "unknown header unit": ("time [s], acceleration [furlong/s^2]\n0 0.1\n0.01 0.2\n", None, None, True),
    "long line": ("0.1 " * 2_000_000 + "\n", "g", 0.01, None),
    "odd AT2": ("title\nevent\nUNITS OF G\nNPTS= 3, DT= -1 SEC\n0.1 0.2 0.3\n", None, None, True),
    "bool dt": ("0.1\n0.2\n0.3\n", "g", True, True),
    "nan dt": ("0.1\n0.2\n0.3\n", "g", float("nan"), True),
    "good two columns": ("time [s], acceleration [g]\n0 0.1\n0.01 0.2\n0.02 0.1\n", None, None, False),
}
RECORD_CLASS = {"three units": "wrong-answer", "header vs option": "wrong-answer", "irregular time with dt":
                "wrong-answer", "uniform time with dt": "wrong-answer", "unknown unit": "units",
                "unknown header unit": "units", "two units": "units", "long line": "sizes"}


@pytest.mark.parametrize("label", list(RECORD_FILES))
def test_record_files(tmp_path, label):
    from rockstudy.model.records import read_record

    text, unit, dt, must_refuse = RECORD_FILES[label]
    path = tmp_path / ("quake.AT2" if label == "odd AT2" else "quake.csv")
    (path.write_bytes if isinstance(text, bytes) else path.write_text)(text)
    t0 = time.perf_counter()
    try:
        record = read_record(path, unit, dt=dt)
        message = None
    except (ValueError, TypeError) as exc:
        message, record = str(exc), None
    took = time.perf_counter() - t0
    if message is None:
        ok = must_refuse is not True and took < SECONDS and math.isfinite(record.pga)
    else:
        ok = must_refuse is not False and readable(message, str(path), "dt", "unit") and took < SECONDS
    verdict(RECORD_CLASS.get(label, "records"), ok,
            f"{label}: {'read' if message is None else message[:200]} ({took:.2f} s)")


@pytest.mark.parametrize("bad", [float("nan"), float("inf")])
def test_a_non_finite_sample_names_the_record(bad):
    from rockstudy.model.records import Record

    try:
        Record(name="p695-far-field:3b", dt=0.01, acceleration=[0.0, 0.1, bad, 0.2])
        message = None
    except ValueError as exc:
        message = str(exc)
    verdict("records", message is not None and readable(message, "p695-far-field:3b"), f"NaN sample: {message}")


# ------------------------------------------------------------------------------------------ the command line

OPTION_CASES = [(option, value) for option in ("--kappa-max", "--damping-ratio", "--noise-level", "--seed",
                                               "--free-time", "--sampling-time", "--width", "--frequency-ratio",
                                               "--amplitude-ratio", "--noise-step", "--sensor-band")
                for value in ("nan", "inf", "-1", "1e300", "true", "")]


def cli_outcome(argv, capsys):
    from rockstudy.cli import main

    t0 = time.perf_counter()
    try:
        status = main(argv)
    except SystemExit as exc:
        status = exc.code
    except Exception as exc:  # a traceback a person would see
        return "traceback", f"{type(exc).__name__}: {exc}\n" * 4, time.perf_counter() - t0
    captured = capsys.readouterr()
    return status, captured.err, time.perf_counter() - t0


@PROPERTY
@given(case=st.sampled_from(OPTION_CASES), command=st.sampled_from(["simulate", "threshold"]))
def test_cli_numeric_options(case, command, capsys, monkeypatch):
    import rockstudy.analysis.scenario as scenario
    import rockstudy.analysis.spectra as spectra

    def stub(*args, **kwargs):
        raise SystemExit(0)
    monkeypatch.setattr(spectra, "threshold", stub)  # a valid input would simulate: stop where it would start
    monkeypatch.setattr(scenario.Scenario, "simulate_motion", stub)
    option, value = case
    status, err, took = cli_outcome([command, f"{option}={value}"], capsys)
    ok = status == 2 and readable(err, option) and took < SECONDS  # every generated value is outside the declaration
    verdict("types" if value in ("true", "") else "ranges", ok, f"{command} {option}={value}: status {status}, "
                                                                 f"{err.strip()[:200]} ({took:.2f} s)")


CONFIG_FILES = {
    "typo": ("realisatons: 3\n", "realisations"),
    "BLC07": ("block: {preset: BLC07}\n", "block.preset"),
    "bad anchorage key": ("anchorage: {kappa_max: 1.0, kappa_min: 0, damping_ratio: 0.05, spring_ultimate_rotation:"
                          " null, damper_ultimate_rotation: null, stiffness: 3}\n", "anchorage.stiffness"),
    "bool seed": ("seed: true\n", "seed"),
    "not a mapping": ("- 1\n- 2\n", "--config"),
    "binary": ("\x00\x01\x02", "--config"),
}


@pytest.mark.parametrize("label", list(CONFIG_FILES))
def test_cli_config_is_a_config_like_any_other(tmp_path, capsys, label):
    text, name = CONFIG_FILES[label]
    path = tmp_path / "mine.yaml"
    path.write_text(text)
    status, err, took = cli_outcome(["simulate", "--config", str(path)], capsys)
    ok = status == 2 and readable(err, name) and took < SECONDS
    verdict("config sections", ok, f"--config {label}: status {status}, {err.strip()[:200]}")


def test_cli_config_alias_bomb(tmp_path, capsys):
    lines = ["a0: &a0 [1, 2, 3, 4, 5, 6, 7, 8, 9]"]
    lines += [f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, 12)]
    path = tmp_path / "bomb.yaml"
    path.write_text("\n".join(lines) + "\n")
    status, err, took = run_with_alarm(lambda: cli_outcome(["simulate", "--config", str(path)], capsys), 10)
    verdict("termination", status == 2 and took < SECONDS, f"--config alias bomb: {status} {err[:200]}")


def test_cli_closed_pipe_ends_quietly():
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    code = "import sys; from rockstudy.cli import main; sys.exit(main(['records']))"
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    p.stdout.readline()
    p.stdout.close()
    err = p.stderr.read().decode()
    status = p.wait(timeout=60)
    verdict("manners", "Traceback" not in err and "BrokenPipe" not in err and status == 141,
            f"records | head -1: status {status}, {err[-300:]}")


@pytest.mark.parametrize("flag", ["--help", "--version"])
def test_cli_help_loads_neither_numba_nor_xarray(flag):
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    code = (f"import sys\nfrom rockstudy.cli import main\ntry:\n    main(['{flag}'])\nexcept SystemExit:\n    pass\n"
            "print(sorted(m for m in ('numba', 'xarray', 'pydantic') if m in sys.modules))")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=60)
    loaded = p.stdout.strip().splitlines()[-1] if p.stdout.strip() else p.stderr
    verdict("manners", loaded == "[]", f"{flag} loads {loaded}")


def test_a_full_disk_keeps_the_spectrum(tmp_path, capsys, monkeypatch):
    """The write of --output fails as on a full disk: one line says so and where the result is kept."""
    import errno
    import tempfile

    real = os.fsync
    calls = []

    def full(fd):
        calls.append(fd)
        if len(calls) == 1:  # the output's write; the kept copy is written
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return real(fd)
    monkeypatch.setattr(os, "fsync", full)
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path / "tmp"))
    (tmp_path / "tmp").mkdir()
    out = tmp_path / "s.nc"
    status, err, took = cli_outcome(["spectrum", "--frequency-start", "2", "--frequency-stop", "2",
                                     "--max-amplitude-ratio", "1.5", "--amplitude-step", "0.3", "--resolution",
                                     "0.3", "--output", str(out)], capsys)
    kept = tmp_path / "tmp" / "rockstudy-kept" / "s.nc"
    ok = (status == 2 and "full" in err and str(kept) in err and kept.exists() and not out.exists()
          and len(err.strip().splitlines()) == 1)
    verdict("faults", ok, f"full disk: status {status}, {err.strip()[:300]}")


# ----------------------------------------------------------------------------------------- the public API

def api_calls():
    """(label, parameter name, call taking the bad value): the constructors and grids of rockstudy.__all__
    and the record reader, one numeric parameter at a time, the others valid."""
    import rockstudy as rs
    from rockstudy.model.noise import NoiseReading

    blc06 = rs.BLOCK_PRESETS["BLC06"]
    calls = [(f"Block.{k}", k, lambda x, k=k: rs.Block(**{"width": 0.4, "height": 1.6, "depth": 0.47, k: x}))
             for k in ("width", "height", "depth", "density", "gravity", "restitution")]
    calls += [(f"Anchorage.{k}", k, lambda x, k=k: rs.Anchorage(**{k: x}))
              for k in ("kappa_max", "kappa_min", "damping_ratio", "spring_ultimate_rotation")]
    calls += [(f"Control.{k}", k, lambda x, k=k: rs.Control("CS01", **{k: x}))
              for k in ("sampling_time", "delay", "sensor_band")]
    calls += [(f"NoiseReading.{k}", k, lambda x, k=k: NoiseReading(**{k: x})) for k in ("step", "band", "span")]
    calls += [(f"AmplitudeGrid.{k}", k, lambda x, k=k: rs.AmplitudeGrid(**{k: x}))
              for k in ("start", "stop", "step", "resolution")]
    calls += [(f"frequency_grid.{k}", k, lambda x, k=k: rs.frequency_grid(**{k: x})) for k in ("start", "stop", "step")]
    calls += [(f"Scenario.{k}", k, lambda x, k=k: rs.Scenario(blc06, **{k: x}))
              for k in ("noise_level", "seed", "free_time")]
    calls += [(f"GroundMotion.{k}", k, lambda x, k=k: rs.GroundMotion(**{"kind": "one-sine", "amplitude": 1.0,
                                                                         "omega": 10.0, "duration": 1.0, k: x}))
              for k in ("amplitude", "omega", "duration")]
    return calls


API_CALLS = api_calls()
API_VALUES = [True, float("nan"), float("inf"), float("-inf"), 0, -1.0, 1e300, 1e-300]


@PROPERTY
@given(call=st.sampled_from(API_CALLS), value=st.sampled_from(API_VALUES))
def test_public_api_by_class(call, value):
    label, param, fn = call
    cls = "types" if isinstance(value, bool) else "ranges"
    t0 = time.perf_counter()
    try:
        result = run_with_alarm(lambda: fn(value), 5)
        message = result if isinstance(result, str) and result.startswith("TIMEOUT") else None
    except (ValueError, TypeError) as exc:
        message = str(exc)
    except Exception as exc:  # anything else is a traceback a person would see
        message = f"{type(exc).__name__}: {exc}\n" * 4
    took = time.perf_counter() - t0
    if message is None:  # accepted: only a finite number, not a bool
        ok = not isinstance(value, bool) and math.isfinite(value) and took < SECONDS
    else:
        ok = readable(message, param) and took < SECONDS
    verdict(cls, ok, f"{label} = {value!r}: {'accepted' if message is None else message[:200]} ({took:.2f} s)")
