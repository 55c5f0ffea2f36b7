"""benchmarks/compare_studies.py: the acceptance rules of a results-moving change, on small made-up
results folders whose differences are known by construction."""
from __future__ import annotations

import csv
import importlib.util
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def cs():
    spec = importlib.util.spec_from_file_location("compare_studies", ROOT / "benchmarks" / "compare_studies.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _write(folder: Path, realisations: np.ndarray, j_os: float = 40.0, verdict: str = "holds") -> Path:
    """A results folder with one noisy spectrum (threshold = lowest over realisations, as the study
    writes it), one table and one claim."""
    (folder / "spectra").mkdir(parents=True)
    (folder / "tables").mkdir()
    (folder / "reproduction").mkdir()
    xr.Dataset({"threshold_realisation": (("realisation", "frequency_ratio"), realisations),
                "threshold": ("frequency_ratio", np.nanmin(realisations, axis=0))}).to_netcdf(
        folder / "spectra" / "CS01_R005.nc")
    xr.Dataset({"j_os": ("strategy", [j_os])}).to_netcdf(folder / "tables" / "table1.nc")
    with open(folder / "reproduction" / "claims.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["claim", "verdict"])
        w.writerow(["c1", verdict])
    return folder


BASE = np.array([[1.50, 2.00, 3.00, 4.00],
                 [1.60, 2.10, 3.10, 4.10],
                 [1.70, 2.20, 3.20, 4.20]])


def test_identical_folders_pass(cs, tmp_path, capsys):
    a, b = _write(tmp_path / "a", BASE), _write(tmp_path / "b", BASE.copy())
    assert cs.main([str(a), str(b)]) == 0
    out = capsys.readouterr().out
    assert "spectrum thresholds: 4 compared, 4 equal" in out
    assert "realisation thresholds: 12 compared, 12 equal" in out


def test_a_realisation_beyond_one_step_fails_that_level_only(cs, tmp_path, capsys):
    moved = BASE.copy()
    moved[2, 1] -= 0.05  # not the lowest realisation: the spectrum's curve stays, one realisation moves
    a, b = _write(tmp_path / "a", BASE), _write(tmp_path / "b", moved)
    assert cs.main([str(a), str(b), "--max-fraction", "0.5"]) == 1
    out = capsys.readouterr().out
    assert "spectrum thresholds: 4 compared, 4 equal, 0 within one step (0.01), 0 beyond" in out
    assert "realisation thresholds: 12 compared, 11 equal, 0 within one step (0.01), 1 beyond" in out
    assert cs.main([str(a), str(b), "--max-fraction", "0.5", "--level", "spectrum"]) == 0
    assert cs.main([str(a), str(b), "--max-fraction", "0.5", "--level", "realisation"]) == 1


def test_the_curve_moves_when_the_lowest_realisation_does(cs, tmp_path, capsys):
    moved = BASE.copy()
    moved[0, 3] -= 0.005  # within one step of 0.01
    moved[0, 0] += 0.5    # the lowest becomes the second: the curve moves by 0.1, beyond one step
    a, b = _write(tmp_path / "a", BASE), _write(tmp_path / "b", moved)
    assert cs.main([str(a), str(b), "--max-fraction", "0.5", "--level", "spectrum"]) == 1
    out = capsys.readouterr().out
    assert "spectrum thresholds: 4 compared, 2 equal, 1 within one step (0.01), 1 beyond" in out


def test_too_many_within_one_step_fail(cs, tmp_path, capsys):
    moved = BASE + 0.01  # every threshold within one step, but all of them differ
    a, b = _write(tmp_path / "a", BASE), _write(tmp_path / "b", moved)
    assert cs.main([str(a), str(b)]) == 1
    assert cs.main([str(a), str(b), "--max-fraction", "1.0"]) == 0


def test_jos_and_claims(cs, tmp_path, capsys):
    a = _write(tmp_path / "a", BASE)
    assert cs.main([str(a), str(_write(tmp_path / "b", BASE, j_os=40.049))]) == 0
    assert cs.main([str(a), str(_write(tmp_path / "c", BASE, j_os=40.1))]) == 1
    assert cs.main([str(a), str(_write(tmp_path / "d", BASE, verdict="fails"))]) == 1
    out = capsys.readouterr().out
    assert "c1: holds -> fails" in out
