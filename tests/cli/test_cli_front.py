"""The command line as a user meets it: --version, defaults in every --help, a block by preset or
dimensions, --config FILE, one-column records, the compact simulate summary."""
import argparse
import json
import math

import numpy as np
import pytest
import yaml

from rockstudy import __version__
from rockstudy.cli import COMMANDS, _apply_config, _DefaultsFormatter, _scenario, build_parser, main
from rockstudy.model.block import BLOCK_PRESETS
from rockstudy.studies import parameters

BLC06 = BLOCK_PRESETS["BLC06"]
CASE = ["--strategy", "CS01", "--frequency-ratio", "2", "--amplitude-ratio", "1.3"]


def run(args, capsys):
    main(args)
    return json.loads(capsys.readouterr().out)


def scenario_of(argv):
    parser = build_parser()
    args = parser.parse_args(argv)
    _apply_config(args, argv, parser)
    return _scenario(args, parser)


def test_version_is_the_package_version(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0 and capsys.readouterr().out.strip() == f"rockstudy {__version__}"


def _subparsers():
    parser = build_parser()
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return action.choices


@pytest.mark.parametrize("command", ["simulate", "threshold", "spectrum", "jos"])
def test_every_help_states_every_default(command):
    sub = _subparsers()[command]
    formatter = _DefaultsFormatter("rockstudy")
    for action in sub._actions:
        if not action.option_strings or action.default in (None, argparse.SUPPRESS, False):
            continue
        assert "default" in formatter._get_help_string(action), action.option_strings
    text = sub.format_help()
    assert "default" in text


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_command_answers_help(command, capsys):
    """``rockstudy COMMAND --help`` prints its help and exits 0 (a ``%`` in a help text breaks argparse)."""
    with pytest.raises(SystemExit) as stop:
        main([command, "--help"])
    assert stop.value.code == 0 and f"usage: rockstudy {command}" in capsys.readouterr().out


def test_spectrum_takes_realisations_not_realisation():
    text = _subparsers()["spectrum"].format_help()
    assert "--realisations" in text and "--realisation " not in text and "--realisation\n" not in text
    with pytest.raises(SystemExit):
        build_parser().parse_args(["spectrum", "--realisation", "2", "--output", "x.nc"])


def test_block_by_dimensions_is_the_preset_and_refuses_both():
    dims = ["--width", str(BLC06.width), "--height", str(BLC06.height), "--depth", str(BLC06.depth),
            "--density", str(BLC06.density)] + ([] if BLC06.restitution is None else
                                                 ["--restitution", str(BLC06.restitution)])
    assert scenario_of(["simulate"] + dims).block == BLC06
    other = scenario_of(["simulate", "--width", "0.3", "--height", "1.5", "--depth", "0.5"]).block
    assert other.width == 0.3 and other.height == 1.5 and other.alpha != BLC06.alpha


@pytest.mark.parametrize("argv, words", [
    (["--block", "BLC06", "--width", "0.4"], "not both"),
    (["--width", "0.4", "--height", "1.6"], "depth"),
    (["--width", "-1", "--height", "1.6", "--depth", "1"], "--width"),
])
def test_bad_block_options_name_the_option(argv, words, capsys):
    with pytest.raises(SystemExit) as stop:
        main(["simulate"] + argv)
    assert stop.value.code == 2 and words in capsys.readouterr().err


def _study_config(tmp_path, **changes):
    config = yaml.safe_load(open(parameters.__file__.replace("src/rockstudy/studies/parameters.py",
                                                              ".test/config.yaml")))
    config.update(changes)
    path = tmp_path / "study.yaml"
    path.write_text(yaml.safe_dump(config))
    return path, config


def test_config_gives_the_study_scenario_and_options_override_it(tmp_path):
    path, config = _study_config(tmp_path, block={"width": 0.5, "height": 1.8, "depth": 0.6},
                                 anchorage={"kappa_max": 0.7, "kappa_min": 0.1, "damping_ratio": 0.02,
                                            "spring_ultimate_rotation": 0.1, "damper_ultimate_rotation": None},
                                 seed=77, free_time=12.0, overturn_criterion="alpha",
                                 noise={"step": 0.005, "rescale": "pga", "level_means": "rms", "band": None,
                                        "span": 1.0})
    study = parameters.scenario_from_dict({
        "block": config["block"], "anchorage": config["anchorage"],
        "control": {"strategy": "CS02", **config["control"]}, "excitation": config["excitation"],
        "noise_level": 0.05, "seed": 77, "noise": config["noise"], "overturn_criterion": "alpha", "free_time": 12.0})
    assert scenario_of(["simulate", "--config", str(path), "--strategy", "CS02", "--noise-level", "0.05"]) == study
    mine = scenario_of(["simulate", "--config", str(path), "--strategy", "CS02", "--noise-level", "0.05",
                        "--kappa-max=0.9", "--seed", "5", "--block", "BLC06"])
    assert mine.anchorage.kappa_max == 0.9 and mine.anchorage.spring_ultimate_rotation == 0.1
    assert mine.seed == 5 and mine.block == BLC06 and mine.free_time == 12.0
    parser = build_parser()
    argv = ["spectrum", "--config", str(path), "--output", "x.nc"]
    args = parser.parse_args(argv)
    _apply_config(args, argv, parser)
    assert (args.min_amplitude_ratio, args.amplitude_step, args.realisations) == (
        config["amplitude_grid"]["start"], config["amplitude_grid"]["step"], config["realisations"])


def test_config_errors_name_the_file(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text("- a list\n")
    with pytest.raises(SystemExit):
        main(["simulate", "--config", str(bad)])
    assert "--config" in capsys.readouterr().err
    path, _ = _study_config(tmp_path, block={"width": 0.4, "height": 1.6})
    with pytest.raises(SystemExit):
        main(["simulate", "--config", str(path)])
    assert "study.yaml" in capsys.readouterr().err


def test_simulate_prints_a_compact_summary_and_keeps_the_events_in_the_output(tmp_path, capsys):
    out = run(["simulate", *CASE, "--output", str(tmp_path / "h.nc")], capsys)
    assert out["n_impacts"] > 100 and out["first_impact_s"] < out["last_impact_s"]
    assert "impact_times_s" not in out and out["max_rotation_ratio"] > 0
    import xarray as xr
    with xr.open_dataset(tmp_path / "h.nc") as ds:
        assert ds.sizes["impact"] == out["n_impacts"] and ds.sizes["uplift"] == out["n_uplifts"]
        assert float(ds["impact_time"][0]) == out["first_impact_s"]
        assert float(ds["impact_time"][-1]) == out["last_impact_s"]


def _one_and_two_columns(tmp_path, t, a):
    """The record ``a`` [g] at times ``t`` written as one column (q.txt, its step given apart) and as two."""
    one, two = tmp_path / "q.txt", tmp_path / "q.csv"
    one.write_text("\n".join(f"{x:.12e}" for x in a) + "\n")
    two.write_text("time [s], acceleration [g]\n" + "".join(f"{ti:.3f}, {x:.12e}\n" for ti, x in zip(t, a)))
    return one, two


def test_one_column_record_with_dt_gives_the_same_run_as_two_columns(tmp_path, capsys):
    t = np.arange(0, 6.0, 0.005)
    a = 0.3 * np.sin(2 * np.pi * 1.0 * t) * np.exp(-((t - 2.5) / 1.2) ** 2)  # in g
    one, two = _one_and_two_columns(tmp_path, t, a)
    a1 = run(["simulate", "--strategy", "CS01", "--record", str(one), "--record-unit", "g", "--record-dt", "0.005"],
             capsys)
    a2 = run(["simulate", "--strategy", "CS01", "--record", str(two)], capsys)
    assert a1["status"] == a2["status"] and a1["n_impacts"] == a2["n_impacts"] > 0
    assert a1["max_rotation_ratio"] == pytest.approx(a2["max_rotation_ratio"], rel=1e-9)
    assert a1["record_npts"] == a2["record_npts"] == t.size
    with pytest.raises(SystemExit):
        main(["simulate", "--record-dt", "0.01"])
    assert "--record-dt" in capsys.readouterr().err


def test_threshold_reads_a_one_column_record_as_simulate_does(tmp_path, capsys):
    t = np.arange(0, 4.0, 0.005)
    a = 0.4 * np.sin(2 * np.pi * 1.2 * t) * np.exp(-((t - 1.5) / 0.8) ** 2)  # in g
    one, two = _one_and_two_columns(tmp_path, t, a)
    scan = ["threshold", "--strategy", "FS", "--max-amplitude-ratio", "3", "--amplitude-step", "0.5",
            "--resolution", "0.05"]
    a1 = run(scan + ["--record", str(one), "--record-unit", "g", "--record-dt", "0.005"], capsys)
    a2 = run(scan + ["--record", str(two)], capsys)
    assert a1["amplitude_ratio"] == a2["amplitude_ratio"] and a1["record_npts"] == a2["record_npts"] == t.size
    for argv in (["threshold", "--record-dt", "0.01"], ["threshold", "--record-unit", "g"]):
        with pytest.raises(SystemExit):
            main(argv)
        err = capsys.readouterr().err
        assert "needs --record" in err and "rockstudy threshold --help" in err


def test_every_command_that_reads_a_record_has_the_same_record_options():
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices
    options = {name: {o for a in sub[name]._actions for o in a.option_strings if o.startswith("--record")}
               for name in ("simulate", "threshold")}
    assert options["threshold"] == {"--record", "--record-unit", "--record-dt"}
    assert options["simulate"] == options["threshold"] | {"--record-scale"}  # a scan finds the scale itself


@pytest.mark.parametrize("argv", [["simulate", "--bogus", "1"], ["threshold", "--frequency", "2"],
                                  ["spectrum", "--output", "x.nc", "--bogus"],
                                  ["jos", "--reference", "a.nc", "--system", "b.nc", "--bogus"]])
def test_an_unknown_option_points_at_the_commands_own_help(argv, capsys):
    with pytest.raises(SystemExit) as exc:
        main(argv)
    err = capsys.readouterr().err
    assert exc.value.code == 2 and len(err.strip().splitlines()) <= 3
    assert f"(the options: rockstudy {argv[0]} --help)" in err and "unrecognized arguments" in err


def test_simulate_and_threshold_print_one_json_style_with_null_for_none(capsys):
    from rockstudy.cli.output import dumps
    for argv in (["simulate"] + CASE, ["threshold", "--strategy", "FS", "--frequency-ratio", "2",
                                       "--max-amplitude-ratio", "2"]):
        main(argv)
        text = capsys.readouterr().out
        out = json.loads(text)
        assert text == dumps(out) + "\n"  # the printer's style: two-space indentation, keys as built
        assert out["noise_band_hz"] is None and out["sensor_band_hz"] is None
        assert "none" not in {v for v in out.values() if isinstance(v, str)} - {out.get("noise_rescale")}


def test_grid_values_are_printed_as_the_grid_has_them(capsys):
    from rockstudy.cli.output import GRID_DECIMALS, grid_values
    midpoint = (1.8 + 1.85) / 2
    assert midpoint != 1.825 and grid_values({"a": midpoint, "b": midpoint}, ["a"]) == {"a": 1.825, "b": midpoint}
    main(["threshold", "--strategy", "CS01", "--frequency-ratio", "2", "--amplitude-step", "0.05",
          "--resolution", "0.005", "--max-amplitude-ratio", "3"])
    text = capsys.readouterr().out
    out = json.loads(text)
    for key in ("amplitude_ratio", "last_safe_amplitude_ratio", "scan_start_amplitude_ratio"):
        assert out[key] == round(out[key], GRID_DECIMALS)
        assert len(repr(out[key]).split(".")[-1]) <= GRID_DECIMALS  # no 1.8250000000000002


def test_simulate_plot_spans_the_whole_run(tmp_path):
    import xarray as xr
    from matplotlib import pyplot as plt

    from rockstudy.plotting import figure_control_history
    main(["simulate"] + CASE + ["--output", str(tmp_path / "h.nc")])
    with xr.open_dataset(tmp_path / "h.nc") as ds:
        ds.load()
    end = float(ds.t[-1])
    assert end > 1.3 * ds.attrs["excitation_end_s"]  # the paper's figures stop before the run ends
    whole = figure_control_history(ds, "cli", whole_run=True)
    paper = figure_control_history(ds, "2")
    assert whole.axes[-1].get_xlim()[1] == pytest.approx(end)
    assert paper.axes[-1].get_xlim()[1] == pytest.approx(1.3 * ds.attrs["excitation_end_s"])
    plt.close("all")


def test_a_non_finite_result_is_one_line_exit_1_and_nothing_printed(monkeypatch, capsys):
    """A result strict JSON cannot carry (NaN, inf) ends the command with one line naming the entry."""
    monkeypatch.setattr("rockstudy.cli.output._first_non_finite", lambda obj, path="": ("records[0].pga_g", math.nan))
    assert main(["records", "--json"]) == 1
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "records[0].pga_g is nan, not a finite number" in err
