"""One default, stated once: the CLI with its defaults, the library's defaults and the study's config.yaml
describe the same study, so every front door gives the same numbers."""
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from rockstudy.analysis.scenario import Scenario
from rockstudy.analysis.spectra import AmplitudeGrid, frequency_grid, spectrum
from rockstudy.cli import _scenario as cli_scenario
from rockstudy.cli import build_parser, main
from rockstudy.model.block import BLOCK_PRESETS
from rockstudy.model.control import Control
from rockstudy.studies import parameters

CONFIG = yaml.safe_load((Path(__file__).parents[1] / "config.yaml").read_text())


def study_scenario(strategy: str, level: str) -> dict:
    """The scenario of a spectrum job as the workflow writes it (workflow/rules/common.smk, ``scenario``)."""
    return {"block": CONFIG["block"], "anchorage": CONFIG["anchorage"],
            "control": {"strategy": strategy, "sampling_time": 0.0, "delay": 0.0, **CONFIG["control"]},
            "excitation": CONFIG["excitation"], "noise_level": CONFIG["noise_levels"][level], "seed": CONFIG["seed"],
            "noise": CONFIG["noise"], "overturn_criterion": CONFIG["overturn_criterion"],
            "free_time": CONFIG["free_time"]}


@pytest.mark.parametrize("strategy", CONFIG["strategies"])
@pytest.mark.parametrize("level", list(CONFIG["noise_levels"]))
def test_cli_defaults_are_the_study_scenario(strategy, level):
    args = build_parser().parse_args(["spectrum", "--strategy", strategy, "--output", "x.nc",
                                      "--noise-level", str(CONFIG["noise_levels"][level])])
    assert cli_scenario(args, None) == parameters.scenario_from_dict(study_scenario(strategy, level))


def test_library_and_cli_grids_are_the_study_grids():
    args = build_parser().parse_args(["spectrum", "--output", "x.nc"])
    grid = AmplitudeGrid(args.min_amplitude_ratio, args.max_amplitude_ratio, args.amplitude_step, args.resolution)
    assert grid == AmplitudeGrid() == parameters.amplitude_grid(CONFIG["amplitude_grid"])
    freqs = frequency_grid(args.frequency_start, args.frequency_stop, args.frequency_step)
    assert np.array_equal(freqs, parameters.frequency_ratios(CONFIG["frequency_grid"]))
    assert np.array_equal(freqs, frequency_grid())
    assert build_parser().parse_args(["jos", "--reference", "a", "--system", "b"]).a_max0 == CONFIG["a_max0"]
    assert Scenario(BLOCK_PRESETS["BLC06"], control=Control("FS"), noise_level=0.05) == \
        parameters.scenario_from_dict(study_scenario("FS", "R005"))


def test_cli_spectrum_with_defaults_is_the_study_spectrum_bit_for_bit(tmp_path, capsys):
    # a small grid given to both doors; every other setting is the CLI's default and config.yaml's value
    small = {"frequency_grid": {"start": 2.0, "stop": 2.5, "step": 0.5},
             "amplitude_grid": {"start": 0.9, "stop": 3.0, "step": 0.3, "resolution": 0.05}}
    fg, ag = small["frequency_grid"], small["amplitude_grid"]
    main(["spectrum", "--strategy", "FS", "--noise-level", "0.05", "--realisations", "2",
          "--frequency-start", str(fg["start"]), "--frequency-stop", str(fg["stop"]),
          "--frequency-step", str(fg["step"]), "--min-amplitude-ratio", str(ag["start"]),
          "--max-amplitude-ratio", str(ag["stop"]), "--amplitude-step", str(ag["step"]),
          "--resolution", str(ag["resolution"]), "--output", str(tmp_path / "cli.nc")])
    capsys.readouterr()
    # the workflow's path (workflow/scripts/spectrum.py) with config.yaml's values
    study = spectrum(parameters.scenario_from_dict(study_scenario("FS", "R005")),
                     parameters.frequency_ratios(fg), realisations=[0, 1], grid=parameters.amplitude_grid(ag))
    with xr.open_dataset(tmp_path / "cli.nc") as cli:
        for name in ("threshold_realisation", "last_safe", "energy_ratio", "pga_ratio", "n_simulations"):
            assert np.array_equal(cli[name].values, study[name].values, equal_nan=True), name
        assert np.isfinite(cli["threshold_realisation"].values).any()
        for key in ("noise_seed", "noise_rescale", "noise_step_s", "free_time_s", "overturn_criterion"):
            assert cli.attrs[key] == study.attrs[key], key
    assert study.attrs["noise_rescale"] == "energy" and study.attrs["noise_seed"] == 20190101
