"""The command line calls each of the library's checks once, naming its options."""
import json

import pytest

from rockstudy.cli import main
from rockstudy.core import quantities, validation

TINY = ["--frequency-start", "1", "--frequency-stop", "2", "--frequency-step", "1", "--min-amplitude-ratio", "0.9",
        "--max-amplitude-ratio", "1.5", "--amplitude-step", "0.3", "--resolution", "0.3"]


def _count(monkeypatch, module, name):
    calls = []
    real = getattr(module, name)

    def counted(*args, **kwargs):
        calls.append((args, kwargs))
        return real(*args, **kwargs)
    monkeypatch.setattr(module, name, counted)
    return calls


def test_spectrum_checks_the_amplitude_grid_once(tmp_path, monkeypatch, capsys, quantity_checks):
    grids = _count(monkeypatch, validation, "check_amplitude_grid")
    frequencies = _count(monkeypatch, validation, "check_grid")
    fields = quantity_checks
    main(["spectrum", "--strategy", "FS", "--output", str(tmp_path / "s.nc")] + TINY)
    assert json.loads(capsys.readouterr().out)["frequencies"] == 2
    grids = [call for call in grids if call[0] == (0.9, 1.5, 0.3, 0.3)]  # not the defaults made at import
    assert len(grids) == 1 and grids[0][1]["names"] == ("--min-amplitude-ratio", "--max-amplitude-ratio",
                                                        "--amplitude-step", "--resolution")
    for option in ("--min-amplitude-ratio", "--max-amplitude-ratio", "--amplitude-step", "--resolution",
                   "--frequency-start", "--frequency-stop", "--frequency-step"):
        assert fields.count(option) == 1, option
    assert [kw["names"] for args, kw in frequencies if args[1:4] == (1.0, 2.0, 1.0)] == [  # the frequency grid
        ("--frequency-start", "--frequency-stop", "--frequency-step")]


@pytest.mark.parametrize("option,value,needle", [
    ("--resolution", "0.5", "--resolution = 0.5 is not allowed: it must not exceed --amplitude-step"),
    ("--max-amplitude-ratio", "0.5", "--max-amplitude-ratio"),
    ("--amplitude-step", "-1", "--amplitude-step"),
    ("--frequency-step", "0", "--frequency-step"),
    ("--frequency-stop", "0.5", "--frequency-stop"),
])
def test_grid_errors_name_the_option(option, value, needle, tmp_path, capsys):
    args = ["spectrum", "--output", str(tmp_path / "s.nc")] + TINY + [option, value]
    with pytest.raises(SystemExit) as exc:
        main(args)
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert needle in err and "AmplitudeGrid" not in err and "Traceback" not in err
    assert len(err.strip().splitlines()) <= 3
    assert not (tmp_path / "s.nc").exists()


# --- every option that sets a library object is checked once, by that object, naming the option -------------

def _object_options():
    """(owner, field, option, quantity) of every option that sets a field of a library object, from the objects'
    declarations (core.quantities.ARGUMENTS) and the CLI's maps of fields to options."""
    from rockstudy.cli import options
    from rockstudy.core.quantities import ARGUMENTS
    maps = {"NoiseReading": options.OPTION_NAMES, "Anchorage": options.OPTION_NAMES, "Control": options.OPTION_NAMES,
            "Scenario": options.SCENARIO_OPTIONS, "Block": {f: f"--{f}" for f in options.BLOCK_OPTIONS}}
    return [(owner, field, names[field], quantity) for owner, names in maps.items()
            for field, quantity in ARGUMENTS[owner].items() if field in names]


OBJECT_OPTIONS = _object_options()
DIMENSIONS = ["--width", "0.4", "--height", "1.6", "--depth", "0.4"]


def _past_the_ends(quantity):
    """Values just outside the declared range (the open ends themselves), as the command line writes them;
    ``quantity`` is a key of QUANTITIES or a Quantity."""
    q = quantity if isinstance(quantity, quantities.Quantity) else quantities.QUANTITIES[quantity]
    out = []
    if q.low is not None:
        out.append(q.low if q.low_open else q.low - max(abs(q.low), 1.0))
    if q.high is not None:
        out.append(q.high if q.high_open else q.high + max(abs(q.high), 1.0))
    return [str(int(x)) if q.integer else f"{x:g}" for x in out]


def test_the_generation_covers_the_objects_options():
    options = {option for _, _, option, _ in OBJECT_OPTIONS}
    assert {"--noise-step", "--noise-band", "--noise-span", "--kappa-max", "--kappa-min", "--damping-ratio",
            "--sampling-time", "--delay", "--sensor-band", "--noise-level", "--seed", "--free-time", "--width",
            "--height", "--depth", "--density", "--restitution"} <= options


@pytest.mark.parametrize("command", ["simulate", "threshold", "spectrum"])
@pytest.mark.parametrize("owner,field,option,quantity", OBJECT_OPTIONS, ids=[o[2] for o in OBJECT_OPTIONS])
def test_a_bad_value_is_refused_once_naming_the_option(command, owner, field, option, quantity, tmp_path, capsys):
    values = _past_the_ends(quantity)
    assert values, f"{quantity} declares no range"
    extra = ["--output", str(tmp_path / "s.nc")] + TINY if command == "spectrum" else []
    for value in values:
        with pytest.raises(SystemExit) as exc:
            main([command, *extra, *DIMENSIONS, f"{option}={value}"])
        assert exc.value.code == 2
        err = capsys.readouterr().err
        lines = err.strip().splitlines()
        assert [line for line in lines if "error" in line] == [lines[0]], err  # one error line
        assert len(lines) <= 3 and lines[0].startswith(f"rockstudy: error: {option} "), err
        assert f"{owner}." not in err and field not in err.replace(option, ""), err  # the option, not the field
        assert "Traceback" not in err
    assert not (tmp_path / "s.nc").exists()


def _run_options():
    """(command, owner, argument, option, quantity) of every option that sets an argument of one run, from the
    declarations of the method or function the command passes it to and the CLI's map of arguments to options."""
    from rockstudy.analysis import spectra  # noqa: F401 -- declares threshold
    from rockstudy.cli import options
    from rockstudy.core.quantities import ARGUMENTS
    owners = {"simulate": "Scenario.motion", "threshold": "threshold"}
    return [(command, owner, arg, options.RUN_OPTIONS[arg], quantity) for command, owner in owners.items()
            for arg, quantity in ARGUMENTS[owner].items()]


RUN_CASES = _run_options()


def test_the_generation_covers_the_run_options():
    assert {(case[0], case[3]) for case in RUN_CASES} == {
        ("simulate", "--frequency-ratio"), ("simulate", "--amplitude-ratio"), ("simulate", "--realisation"),
        ("threshold", "--frequency-ratio"), ("threshold", "--realisation")}


@pytest.mark.parametrize("command,owner,arg,option,quantity", RUN_CASES, ids=[f"{c[0]}{c[3]}" for c in RUN_CASES])
def test_a_bad_run_option_is_refused_once_naming_it(command, owner, arg, option, quantity, monkeypatch, capsys):
    from rockstudy.studies import config_model
    by_option = _count(monkeypatch, config_model, "check_option")
    values = _past_the_ends(quantity)
    assert len(values) == 2, quantity
    for value in values:
        with pytest.raises(SystemExit) as exc:
            main([command, *DIMENSIONS, f"{option}={value}"] + (TINY[8:] if command == "threshold" else []))
        assert exc.value.code == 2
        err = capsys.readouterr().err
        lines = err.strip().splitlines()
        assert [line for line in lines if "error" in line] == [lines[0]], err
        assert len(lines) <= 3 and lines[0].startswith(f"rockstudy: error: {option} = "), err
        assert arg not in err.replace(option, "") and "Traceback" not in err, err
    assert by_option == []  # the CLI did not check it first


def test_simulate_checks_each_object_option_once(monkeypatch, capsys, quantity_checks):
    checked = quantity_checks
    from rockstudy.studies import config_model
    by_option = _count(monkeypatch, config_model, "check_option")
    given = {"--noise-level": "0.05", "--seed": "7", "--free-time": "2", "--noise-step": "0.005",
             "--noise-band": "20", "--noise-span": "0.5", "--kappa-max": "1.5", "--kappa-min": "0.1",
             "--damping-ratio": "0.1", "--sampling-time": "0.01", "--delay": "0.01", "--sensor-band": "20",
             "--density": "2500", "--restitution": "0.9"}
    runs = {"--frequency-ratio": "2", "--amplitude-ratio": "1.2", "--realisation": "1"}
    main(["simulate", "--strategy", "CS02", *DIMENSIONS]
         + [word for pair in {**given, **runs}.items() for word in pair])
    assert json.loads(capsys.readouterr().out)["strategy"] == "CS02"
    for option in [case[2] for case in OBJECT_OPTIONS] + list(runs):
        assert checked.count(option) == 1, (option, checked.count(option))
    # not checked again under the field's own name (block_from_dict builds the block once, naming the options)
    fields = {f"{prefix}.{field}" for owner, field, _, _ in OBJECT_OPTIONS
              for prefix in (owner, "block") if prefix == owner or owner == "Block"}
    assert not fields & set(checked), sorted(fields & set(checked))
    # a run's frequency, amplitude and realisation are checked once, by Scenario.motion, not by the CLI first
    assert by_option == []
    again = {"frequency_ratio", "amplitude_ratio"} & set(checked)  # (noisy_record takes the realisation on)
    assert not again, sorted(again)


def test_threshold_checks_each_run_option_once(monkeypatch, capsys, quantity_checks):
    checked = quantity_checks
    from rockstudy.studies import config_model
    by_option = _count(monkeypatch, config_model, "check_option")
    main(["threshold", "--strategy", "FS", "--frequency-ratio", "2", "--noise-level", "0.05", "--realisation", "1",
          *DIMENSIONS] + TINY[8:])
    assert json.loads(capsys.readouterr().out)["realisation"] == 1
    assert checked.count("--frequency-ratio") == 1 and checked.count("--realisation") == 1
    assert by_option == []


# --- a record's step is checked once, by read_record, naming --record-dt -------------------------------------

@pytest.fixture
def one_column(tmp_path):
    path = tmp_path / "record.txt"
    path.write_text("0.0\n0.1\n-0.2\n0.05\n0.0\n")
    return str(path)


@pytest.mark.parametrize("command", ["simulate", "threshold"])
def test_a_bad_record_step_is_refused_once_naming_it(command, one_column, monkeypatch, capsys):
    from rockstudy.core.quantities import ARGUMENTS
    from rockstudy.model import records  # noqa: F401 -- declares read_record
    from rockstudy.studies import config_model
    by_option = _count(monkeypatch, config_model, "check_option")
    values = _past_the_ends(ARGUMENTS["read_record"]["dt"])
    assert len(values) == 2
    for value in values:
        with pytest.raises(SystemExit) as exc:
            main([command, "--record", one_column, "--record-unit", "g", f"--record-dt={value}"])
        assert exc.value.code == 2
        err = capsys.readouterr().err
        lines = err.strip().splitlines()
        assert len(lines) <= 3 and lines[0].startswith("rockstudy: error: --record-dt = "), err
        assert "dt " not in err.replace("--record-dt", "") and "Traceback" not in err, err
    assert [args[0] for args, _ in by_option if args[0] == "--record-dt"] == []


def test_a_record_step_is_checked_once(one_column, monkeypatch, capsys, quantity_checks):
    checked = quantity_checks
    from rockstudy.studies import config_model
    by_option = _count(monkeypatch, config_model, "check_option")
    main(["simulate", "--record", one_column, "--record-unit", "g", "--record-dt", "0.01"])
    assert json.loads(capsys.readouterr().out)["record_dt_s"] == 0.01
    assert checked.count("--record-dt") == 1
    assert "--record-dt" not in [args[0] for args, _ in by_option]


# --- risk and fragility: each option checked once, by the library, before any file is read -----------------

def _checks_and_reads(monkeypatch, module, name):
    """Log each Quantity.check (the name it gives, the module that calls it) and each call of ``module.name`` (a
    reader), in order."""
    import sys
    log = []
    real_check, real_read = quantities.Quantity.check, getattr(module, name)

    def check(self, label, value):
        log.append((label, sys._getframe(1).f_globals["__name__"]))
        return real_check(self, label, value)

    def read(*args, **kwargs):
        log.append(("READ", name))
        return real_read(*args, **kwargs)
    monkeypatch.setattr(quantities.Quantity, "check", check)
    monkeypatch.setattr(module, name, read)
    return log


def _risk_cases():
    """(option, quantity, command line without the option) of every number of ``rockstudy risk``, in each mode
    that uses it; the hazard file does not exist, so a check after reading it would name the file instead."""
    from rockstudy.cli.risk import RISK_OPTIONS
    frag, hazard = ["--median", "0.5", "--dispersion", "0.4"], ["--hazard", "no-such-hazard.txt"]
    rate, probability = ["--dispersion", "0.4", "--target-rate", "1e-4"], ["--dispersion", "0.4",
                                                                          "--target-probability", "0.01"]
    modes = {"median_g": [frag], "dispersion": [frag, rate], "years": [frag, probability, rate],
             "target_rate": [rate], "target_probability": [probability]}
    assert set(modes) == set(RISK_OPTIONS)
    return [(option, key, line, hazard) for key, option in RISK_OPTIONS.items() for line in modes[key]]


def _drop(line, option):
    """``line`` without ``option`` and its value."""
    if option not in line:
        return line
    i = line.index(option)
    return line[:i] + line[i + 2:]


RISK_CASES = _risk_cases()


@pytest.mark.parametrize("option,key,line,hazard", RISK_CASES, ids=[f"{c[0]}{i}" for i, c in enumerate(RISK_CASES)])
def test_a_bad_risk_option_is_refused_once_before_the_hazard_file(option, key, line, hazard, monkeypatch, capsys):
    from rockstudy.analysis import hazard as hazard_module
    from rockstudy.core.risk_inputs import RISK_INPUTS
    log = _checks_and_reads(monkeypatch, hazard_module, "read_hazard_sites")
    values = _past_the_ends(RISK_INPUTS[key])
    assert len(values) == 2, key
    for value in values:
        with pytest.raises(SystemExit) as exc:
            main(["risk", *_drop(line, option), *hazard, f"{option}={value}"])
        assert exc.value.code == 2
        err = capsys.readouterr().err
        lines = err.strip().splitlines()
        assert [x for x in lines if "error" in x] == [lines[0]], err
        assert len(lines) <= 3 and lines[0].startswith(f"rockstudy: error: {option} = "), err
        assert key not in err.replace(option, "") and "Traceback" not in err and "no-such" not in err, err
    assert ("READ", "read_hazard_sites") not in log
    callers = [m for label, m in log if label == option]
    assert len(callers) == 2 and all(m.startswith("rockstudy.analysis.") for m in callers), log  # the library


def _risk_run(args, log, capsys):
    main(["risk", *args])
    out = json.loads(capsys.readouterr().out)
    checked = [label for label, _ in log if label != "READ"]
    return out, checked, log.index(("READ", "read_hazard_sites"))


@pytest.fixture
def power_law_hazard(tmp_path):
    import numpy as np
    x = np.geomspace(0.001, 5.0, 50)
    path = tmp_path / "site.txt"
    path.write_text("".join(f"{float(a)!r}, {float(1e-4 * a ** -2.5)!r}\n" for a in x))
    return str(path)


def test_risk_checks_each_option_once_by_the_library_before_reading(power_law_hazard, monkeypatch, capsys):
    from rockstudy.analysis import hazard as hazard_module
    log = _checks_and_reads(monkeypatch, hazard_module, "read_hazard_sites")
    out, checked, read = _risk_run(["--median", "0.6", "--dispersion", "0.4", "--years", "30", "--hazard",
                                    power_law_hazard], log, capsys)
    assert out["years"] == 30 and out["median_g"] == 0.6
    for option in ("--median", "--dispersion", "--years"):
        (i,) = [i for i, (label, _) in enumerate(log) if label == option]
        assert i < read and log[i][1].startswith("rockstudy.analysis."), (option, log[i])
    assert not {"median_g", "dispersion", "years"} & set(checked), checked  # not again under the library's names
    for target in (["--target-rate", "1e-3"], ["--target-probability", "0.05"]):
        log.clear()
        out, checked, read = _risk_run(["--dispersion", "0.4", "--years", "30", "--hazard", power_law_hazard,
                                        *target], log, capsys)
        assert out["years"] == 30 and out["median_g"] > 0
        for option in ("--dispersion", "--years", target[0]):
            (i,) = [i for i, (label, _) in enumerate(log) if label == option]
            assert i < read and log[i][1].startswith("rockstudy.analysis."), (option, log[i])
        assert not {"years", "target_rate", "target_probability"} & set(checked), checked


def _fragility_cases():
    from rockstudy.analysis import fragility  # noqa: F401 -- declares suite_fragility_dataset
    from rockstudy.cli.risk import FRAGILITY_OPTIONS
    from rockstudy.core.quantities import ARGUMENTS
    declared = ARGUMENTS["suite_fragility_dataset"]
    assert set(FRAGILITY_OPTIONS) == set(declared)
    return [(option, declared[arg]) for arg, option in FRAGILITY_OPTIONS.items()]


FRAGILITY_CASES = _fragility_cases()
FRAGILITY = ["fragility", "--strategy", "FS", "--suite", "p695-far-field", "--max-records", "1", "--levels-start",
             "1", "--levels-stop", "2", "--levels-step", "1", "--threshold-resolution", "0.5", "--bootstrap", "0"]


@pytest.mark.parametrize("option,quantity", FRAGILITY_CASES, ids=[c[0] for c in FRAGILITY_CASES])
def test_a_bad_fragility_option_is_refused_once_before_the_records(option, quantity, tmp_path, monkeypatch, capsys):
    from rockstudy.model import record_suites
    log = _checks_and_reads(monkeypatch, record_suites, "load_suite")
    values = _past_the_ends(quantity)
    assert values, quantity
    for value in values:
        with pytest.raises(SystemExit) as exc:
            main([*_drop(FRAGILITY, option), "--output", str(tmp_path / "f.nc"), f"{option}={value}"])
        assert exc.value.code == 2
        err = capsys.readouterr().err
        lines = err.strip().splitlines()
        assert [x for x in lines if "error" in x] == [lines[0]], err
        assert len(lines) <= 3 and lines[0].startswith(f"rockstudy: error: {option} = "), err
        assert "suite_fragility_dataset" not in err and "Traceback" not in err, err
    assert ("READ", "load_suite") not in log
    assert {m for label, m in log if label == option} == {"rockstudy.core.quantities"}, log  # check_arguments
    assert not (tmp_path / "f.nc").exists()


def test_fragility_checks_each_option_once_by_the_library_before_the_records(tmp_path, monkeypatch, capsys):
    from rockstudy.model import record_suites
    log = _checks_and_reads(monkeypatch, record_suites, "load_suite")
    main([*FRAGILITY, "--free-time", "2", "--seed", "3", "--output", str(tmp_path / "f.nc")])
    assert json.loads(capsys.readouterr().out)["n_records"] == 1
    read = log.index(("READ", "load_suite"))
    for option, _ in FRAGILITY_CASES:
        (i,) = [i for i, (label, _) in enumerate(log) if label == option]
        assert i < read and log[i][1] == "rockstudy.core.quantities", (option, log[i])  # by check_arguments


# --- jos: --a-max0 checked once, by jos, before the spectra are read ----------------------------------------

def _spectrum_file(path):
    import numpy as np
    import xarray as xr

    from rockstudy.core import io
    from rockstudy.model.block import BLOCK_PRESETS
    from rockstudy.studies import datasets
    ds = datasets.document_missing(xr.Dataset(
        {"threshold": ("frequency_ratio", [np.nan, 2.0])}, coords={"frequency_ratio": [1.0, 2.0]},
        attrs={**BLOCK_PRESETS["BLC06"].to_attrs(), "grid_amplitude_start": 0.9, "grid_amplitude_stop": 4.5,
               "grid_amplitude_step": 0.6}))
    io.write_netcdf(ds, path)
    return str(path)


def test_a_bad_a_max0_is_refused_once_before_the_spectra(monkeypatch, capsys):
    from rockstudy.analysis import jos  # noqa: F401 -- declares jos
    from rockstudy.core import io
    from rockstudy.core.quantities import ARGUMENTS
    log = _checks_and_reads(monkeypatch, io, "read_netcdf")
    values = _past_the_ends(ARGUMENTS["jos"]["a_max0_g"])
    assert len(values) == 2
    for value in values:
        with pytest.raises(SystemExit) as exc:
            main(["jos", "--reference", "no-such-ref.nc", "--system", "no-such-sys.nc", f"--a-max0={value}"])
        assert exc.value.code == 2
        err = capsys.readouterr().err
        lines = err.strip().splitlines()
        assert len(lines) <= 3 and lines[0].startswith("rockstudy: error: --a-max0 = "), err
        assert "no-such" not in err and "Traceback" not in err, err
    assert ("READ", "read_netcdf") not in log
    assert [m for label, m in log if label == "--a-max0"] == ["rockstudy.core.quantities"] * 2, log


def test_jos_checks_a_max0_once_before_reading(tmp_path, monkeypatch, capsys):
    from rockstudy.core import io
    from rockstudy.studies import config_model
    path = _spectrum_file(tmp_path / "a.nc")
    by_option = _count(monkeypatch, config_model, "check_option")
    log = _checks_and_reads(monkeypatch, io, "read_netcdf")
    main(["jos", "--reference", path, "--system", path, "--a-max0", "0.2"])
    assert json.loads(capsys.readouterr().out)["a_max0_g"] == 0.2
    (i,) = [i for i, (label, _) in enumerate(log) if label == "--a-max0"]
    assert i < log.index(("READ", "read_netcdf")) and log[i][1] == "rockstudy.core.quantities", log
    assert by_option == []
