import json
import subprocess
import sys

import pytest

from rockstudy.cli import main


def run(args, capsys):
    main(args)
    return json.loads(capsys.readouterr().out)


def test_simulate_prints_json_and_writes_history(tmp_path, capsys):
    out = run(["simulate", "--strategy", "CS02", "--frequency-ratio", "2", "--amplitude-ratio", "1.4",
               "--noise-level", "0.05", "--realisation", "3", "--sampling-time", "0.1", "--delay", "0.06",
               "--output", str(tmp_path / "h.nc")], capsys)
    assert out["status"] in ("rest", "overturned", "time limit")
    assert out["energy_ratio"] == pytest.approx(1.0)
    import xarray as xr
    with xr.open_dataset(tmp_path / "h.nc") as ds:
        assert ds.theta.attrs["units"] == "rad" and ds.attrs["control_strategy"] == "CS02"


def test_threshold_matches_library_and_null_above_bound(capsys, blc06):
    from rockstudy import Control
    from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, threshold
    out = run(["threshold", "--strategy", "FS", "--frequency-ratio", "2", "--max-amplitude-ratio", "3"], capsys)
    lib = threshold(Scenario(blc06, control=Control("FS")), 2.0, grid=AmplitudeGrid(stop=3.0))
    assert out["amplitude_ratio"] == lib["amplitude_ratio"]
    out = run(["threshold", "--strategy", "CS01", "--frequency-ratio", "4.5", "--max-amplitude-ratio", "1.5"], capsys)
    assert out["amplitude_ratio"] is None


def test_spectrum_and_jos(tmp_path, capsys):
    common = ["--frequency-start", "1", "--frequency-stop", "3", "--frequency-step", "1",
              "--amplitude-step", "0.3", "--resolution", "0.05", "--max-amplitude-ratio", "4.2"]
    run(["spectrum", "--strategy", "FS", "--output", str(tmp_path / "fs.nc")] + common, capsys)
    run(["spectrum", "--strategy", "CS01", "--output", str(tmp_path / "cs.nc")] + common, capsys)
    out = run(["jos", "--reference", str(tmp_path / "fs.nc"), "--system", str(tmp_path / "cs.nc")], capsys)
    assert -100 <= out["J_OS_percent"] <= 100 and out["N_star"] >= 1
    same = run(["jos", "--reference", str(tmp_path / "fs.nc"), "--system", str(tmp_path / "fs.nc")], capsys)
    assert same["J_OS_percent"] == 0.0


@pytest.mark.parametrize("args,needle", [
    (["threshold", "--strategy", "CS03"], "--strategy"),
    (["threshold", "--sampling-time", "-0.1"], "--sampling-time"),
    (["threshold", "--noise-level", "1.0"], "--noise-level"),
    (["simulate", "--delay", "0.06"], "--delay"),
    (["threshold", "--resolution", "0.5"], "--resolution"),
    (["threshold", "--excitation", "kobe"], "--excitation"),
    (["threshold", "--kappa-min", "2"], "--kappa-min (2.0) must not exceed --kappa-max (1.0)"),
    (["simulate", "--sampling-time", "0", "--delay", "0.06"], "--delay > 0 needs a --sampling-time > 0"),
])
def test_bad_arguments_exit_nonzero_naming_the_argument(args, needle):
    p = subprocess.run([sys.executable, "-m", "rockstudy.cli"] + args, capture_output=True, text=True)
    assert p.returncode == 2
    assert needle in p.stderr


def test_jos_rejects_different_grids(tmp_path, capsys):
    base = ["--amplitude-step", "0.3", "--resolution", "0.05", "--max-amplitude-ratio", "3", "--frequency-step", "1"]
    run(["spectrum", "--strategy", "FS", "--frequency-start", "1", "--frequency-stop", "2",
         "--output", str(tmp_path / "a.nc")] + base, capsys)
    run(["spectrum", "--strategy", "FS", "--frequency-start", "1", "--frequency-stop", "3",
         "--output", str(tmp_path / "b.nc")] + base, capsys)
    with pytest.raises(SystemExit) as exc:
        main(["jos", "--reference", str(tmp_path / "a.nc"), "--system", str(tmp_path / "b.nc")])
    assert exc.value.code == 2
    assert "frequency grids" in capsys.readouterr().err


def test_noise_options_reach_the_records(tmp_path, capsys, blc06):
    from rockstudy import Control
    from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, threshold
    from rockstudy.model.noise import NoiseReading
    args = ["threshold", "--strategy", "FS", "--frequency-ratio", "2", "--noise-level", "0.1", "--realisation", "1",
            "--max-amplitude-ratio", "3", "--noise-step", "0.01", "--noise-rescale", "none",
            "--noise-level-means", "rms", "--noise-band", "20", "--noise-span", "0.5"]
    out = run(args, capsys)
    reading = NoiseReading(step=0.01, rescale="none", level_means="rms", band=20.0, span=0.5)
    assert (out["noise_step_s"], out["noise_rescale"], out["noise_level_means"], out["noise_band_hz"],
            out["noise_span_s"]) == (0.01, "none", "rms", 20.0, 0.5)
    lib = threshold(Scenario(blc06, control=Control("FS"), noise_level=0.1, noise=reading), 2.0, realisation=1,
                    grid=AmplitudeGrid(stop=3.0))
    assert out["amplitude_ratio"] == lib["amplitude_ratio"] and out["energy_ratio"] == lib["energy_ratio"]
    assert out["energy_ratio"] != pytest.approx(1.0, abs=1e-6)  # "none" keeps the sum unscaled
    out = run(["simulate", "--strategy", "FS", "--noise-level", "0.05", "--noise-rescale", "pga"], capsys)
    assert out["noise_rescale"] == "pga" and out["noise_step_s"] == 0.0025 and out["pga_ratio"] == pytest.approx(1.0)
    assert "noise_match" not in out and "noise_dt_s" not in out
    with pytest.raises(SystemExit) as exc:  # the former spelling is gone
        main(["simulate", "--noise-level", "0.05", "--match", "pga"])
    assert exc.value.code == 2


@pytest.mark.parametrize("args, name", [(["--noise-step", "0"], "--noise-step"),
                                        (["--noise-band", "500"], "--noise-band"),
                                        (["--noise-span", "-1"], "--noise-span"),
                                        (["--noise-rescale", "rms"], "--noise-rescale")])
def test_bad_noise_options_exit_2_naming_the_option(args, name, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["simulate", "--noise-level", "0.05"] + args)
    assert exc.value.code == 2
    assert name in capsys.readouterr().err
