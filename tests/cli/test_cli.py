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


# --- jos refuses spectra made under different settings -----------------------------------------------
def _jos_pair(tmp_path, **changes):
    """A CS01 spectrum with ``changes`` and an FS reference with the defaults, both noisy, as files."""
    from builders import fake_spectrum
    from rockstudy.core.io import write_netcdf
    thr = [[1.2, 1.5, 3.0, 2.0], [1.3, 1.4, 3.5, 2.5]]
    write_netcdf(fake_spectrum("FS", 0.05, thr), tmp_path / "ref.nc")
    write_netcdf(fake_spectrum("CS01", 0.05, [[1.4, 1.7, 3.2, 2.2]] * 2, **changes), tmp_path / "sys.nc")
    return ["jos", "--reference", str(tmp_path / "ref.nc"), "--system", str(tmp_path / "sys.nc")]


def _mismatches():
    from builders import BLC06
    from rockstudy import Anchorage, Block
    from rockstudy.analysis.spectra import AmplitudeGrid
    from rockstudy.model.noise import NoiseReading
    return [({"excitation": "one-sine"}, "excitation"), ({"overturn_criterion": "alpha"}, "overturn_criterion"),
            ({"free_time": 10.0}, "free_time_s"), ({"seed": 1}, "noise_seed"),
            ({"noise": NoiseReading(step=0.005)}, "noise_step_s"), ({"noise": NoiseReading(rescale="none")},
                                                                    "noise_rescale"),
            ({"noise": NoiseReading(level_means="rms")}, "noise_level_means"),
            ({"noise": NoiseReading(band=5.0)}, "noise_band_hz"), ({"noise": NoiseReading(span=5.0)}, "noise_span_s"),
            ({"realisations": [0, 1, 2]}, "n_realisations"),
            ({"block": Block(BLC06.width, BLC06.height * 1.1, BLC06.depth)}, "block_"),
            ({"anchorage": Anchorage(kappa_max=2.0)}, "anchorage_"),
            ({"grid": AmplitudeGrid(resolution=0.05)}, "grid_amplitude_resolution"),
            ({"grid": AmplitudeGrid(stop=5.0)}, "grid_amplitude_stop")]


@pytest.mark.parametrize("case", range(14))
def test_jos_refuses_each_mismatched_setting_unless_allowed(tmp_path, capsys, case):
    changes, attr = _mismatches()[case]
    if "realisations" in changes:
        changes = {"realisations": None}
        from builders import fake_spectrum
        from rockstudy.core.io import write_netcdf
        args = _jos_pair(tmp_path)
        write_netcdf(fake_spectrum("CS01", 0.05, [[1.4, 1.7, 3.2, 2.2]] * 3), tmp_path / "sys.nc")
    else:
        args = _jos_pair(tmp_path, **changes)
    with pytest.raises(SystemExit) as exc:
        main(args)
    err = capsys.readouterr().err
    assert exc.value.code == 2 and f"settings: {attr}" in err and "in --system and" in err, err
    named = err.split("settings: ")[1].split(" is ")[0]
    out = run(args + ["--allow-mismatch", named], capsys) if not attr.endswith("_") else None
    if out is not None:
        assert out["N_star"] >= 1
    assert run(args + ["--allow-mismatch", "all"], capsys)["N_star"] >= 1


def test_jos_accepts_spectra_that_differ_only_in_what_it_compares(tmp_path, capsys):
    from builders import fake_spectrum
    from rockstudy.core.io import write_netcdf
    write_netcdf(fake_spectrum("CS02", 0.05, [[1.4, 1.7, 3.2, 2.2]], sampling_time=0.1), tmp_path / "sys.nc")
    write_netcdf(fake_spectrum("CS02", 0.0, [[1.2, 1.5, 3.0, 2.0]], seed=9), tmp_path / "ref.nc")
    out = run(["jos", "--reference", str(tmp_path / "ref.nc"), "--system", str(tmp_path / "sys.nc")], capsys)
    assert out["N_star"] == 4


@pytest.mark.parametrize("spoil, needle", [
    (lambda ds: ds.attrs.update(block_alpha=0.0), "block_alpha = 0.0 is not allowed"),
    (lambda ds: ds.attrs.pop("grid_amplitude_stop"), "no attribute 'grid_amplitude_stop'"),
    (lambda ds: ds.attrs.update(grid_amplitude_step="x"), "grid_amplitude_step = 'x' is not a number"),
    (lambda ds: ds.attrs.update(grid_amplitude_start=float("nan")), "grid_amplitude_start = nan"),
])
def test_jos_names_what_is_wrong_with_an_almost_spectrum(tmp_path, capsys, spoil, needle):
    import xarray as xr

    from rockstudy.core.io import write_netcdf
    args = _jos_pair(tmp_path)
    with xr.open_dataset(tmp_path / "sys.nc") as ds:
        ds = ds.load()
    spoil(ds)
    write_netcdf(ds, tmp_path / "sys.nc")
    with pytest.raises(SystemExit) as exc:
        main(args)
    assert exc.value.code == 2 and needle in capsys.readouterr().err


def test_jos_and_record_refuse_fifos_folders_and_devices_quickly(tmp_path):
    import os
    import time
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    for args, needle in [(["jos", "--reference", str(fifo), "--system", str(fifo)], "not a regular file"),
                         (["jos", "--reference", str(tmp_path), "--system", str(fifo)], "is a folder"),
                         (["simulate", "--record", "/dev/zero"], "not a regular file"),
                         (["simulate", "--record", str(fifo)], "not a regular file"),
                         (["simulate", "--record", str(tmp_path)], "is a folder")]:
        t0 = time.monotonic()
        p = subprocess.run([sys.executable, "-m", "rockstudy.cli"] + args, capture_output=True, text=True, timeout=60)
        assert p.returncode == 2 and needle in p.stderr, p.stderr
        assert time.monotonic() - t0 < 30


def test_a_refused_output_leaves_no_folders_behind(tmp_path):
    p = subprocess.run([sys.executable, "-m", "rockstudy.cli", "simulate", "--record", str(tmp_path / "none.csv"),
                        "--output", str(tmp_path / "new" / "a" / "b" / "x.nc")], capture_output=True, text=True)
    assert p.returncode == 2 and "does not exist" in p.stderr
    assert not (tmp_path / "new").exists()
