"""Design charts: the similarity of the rocking block's spectra, the device sweep, the gathered sweeps."""
import math

import numpy as np
import pytest

from rockstudy import AmplitudeGrid, Block, Scenario, spectrum
from rockstudy.model.records import Record
from rockstudy.studies import design


def test_spectra_in_dimensionless_form_do_not_depend_on_size():
    """Similarity (Dimitrakopoulos and DeJong 2012): a_p/(g tan alpha) against omega_p/p of the free-standing
    block depends on alpha only. The equation of motion in tau = p t holds only alpha, a_p/g and omega_p/p,
    and the engine's step bound and rest velocity scale with p, so two blocks of alpha = 0.15 with R = 0.5 m
    and 2 m must agree to the bisection's resolution (0.01), the only tolerance left when an adaptive step in
    seconds decides an outcome right at the bracket's edge; they are found identical."""
    grid = AmplitudeGrid(start=0.9, stop=6.0, step=0.1, resolution=0.01)
    freqs = [1.0, 2.0, 3.0]
    small, large = (spectrum(Scenario(Block.slender(0.15, R)), freqs, grid=grid, progress_chunks=1)["threshold"].values
                    for R in (0.5, 2.0))
    assert np.all(np.isfinite(small)) and np.all(np.isfinite(large))
    assert np.max(np.abs(small - large)) <= grid.resolution


def step_pulse(duration, dt=0.01):
    """A constant unit ground acceleration for ``duration`` seconds (a one-sample ramp at each end)."""
    values = np.ones(int(round(duration / dt)) + 1)
    values[0] = values[-1] = 0.0
    return Record(f"step{duration:g}", dt, values)


def test_a_stiffer_passive_device_raises_the_median_under_long_pushes(blc06):
    """PASSIVE (spring always on, kappa_min = kappa_max), no damping, long constant pushes (4-8 s, far longer
    than 1/p = 0.33 s): along the same path to theta = alpha the push does the same work whatever the spring,
    while the energy the spring stores on the way grows with kappa_max; beyond alpha the springs are broken.
    So the overturning PGA of each record, and the median, cannot fall as kappa_max grows, and rises once the
    spring can hold the block against the push."""
    records = [step_pulse(T) for T in (4.0, 6.0, 8.0)]
    levels = design.pga_levels(0.2, 2.0, 40)
    medians = [float(design.device_point(blc06, k, 0.0, ["PASSIVE"], records, levels, suite="steps",
                                         free_time=10.0).fragility_median.values[0]) for k in (0.0, 1.0, 2.0, 4.0)]
    assert all(np.isfinite(medians))
    assert all(b >= a for a, b in zip(medians, medians[1:])), medians
    assert medians[-1] > 1.3 * medians[0] and medians[-1] > medians[-2] > medians[1], medians


def test_gathered_sweeps_and_the_design_answer(blc06):
    """Points gathered over (kappa_max, xi) and the smallest kappa_max reaching a target, read off the table."""
    import xarray as xr
    points = []
    for k, m in ((0.5, 0.7), (1.0, 0.9), (2.0, 1.1)):
        points.append(xr.Dataset({"fragility_median": ("strategy", [0.6, m]), "fit_status": ("strategy", ["ok"] * 2)},
                                 coords={"strategy": ["FS", "CS01"], "kappa_max": k, "damping_ratio": 0.05},
                                 attrs={"record_suite": "s", "n_records": 3, "compute_time_s": 1.0}))
    devices = design.gather_devices(points)
    assert devices.fragility_median.sel(strategy="CS01", damping_ratio=0.05).values.tolist() == [0.7, 0.9, 1.1]
    assert design.smallest_kappa(devices, "CS01", 0.05, 0.85) == 1.0
    assert math.isnan(design.smallest_kappa(devices, "CS01", 0.05, 2.0))
    text = design.design_markdown(devices, 0.85, "block BLC06")
    assert "CS01 with ξ = 0.05 and κ_max ≥ 1 keeps the median above 0.85 g" in text


def test_pga_levels_are_geometric():
    levels = design.pga_levels(0.1, 1.0, 3)
    np.testing.assert_allclose(levels, [0.1, math.sqrt(0.1), 1.0])
    with pytest.raises(ValueError):
        design.pga_levels(1.0, 0.5, 3)


def test_the_design_answer_says_when_the_medians_interval_holds_the_target():
    """A median above the target whose 95 % interval reaches below it: the sentence that gives the answer says
    the records do not settle it (CS02 at kappa_max = 1 of the default design: 0.884 g, 0.848-0.922 g against
    0.9 g, is the case this guards); an interval wholly above the target gets no such note."""
    import xarray as xr
    points = []
    for k, (m, lo, hi) in ((0.5, (0.80, 0.75, 0.85)), (1.0, (0.92, 0.88, 0.96)), (2.0, (1.1, 1.05, 1.15))):
        points.append(xr.Dataset({"fragility_median": ("strategy", [0.6, m]),
                                  "fragility_median_low": ("strategy", [0.55, lo]),
                                  "fragility_median_high": ("strategy", [0.65, hi])},
                                 coords={"strategy": ["FS", "CS02"], "kappa_max": k, "damping_ratio": 0.05},
                                 attrs={"record_suite": "s", "n_records": 3, "compute_time_s": 1.0}))
    devices = design.gather_devices(points)
    assert devices.fragility_median_low.sel(strategy="CS02", damping_ratio=0.05).values.tolist() == [0.75, 0.88, 1.05]
    held = design.design_markdown(devices, 0.9, "block BLC06")  # the answer's own interval reaches below
    assert "κ_max ≥ 1 keeps the median above 0.9 g" in held
    assert "its 95 % interval, 0.880–0.960 g, reaches below the target" in held
    below = design.design_markdown(devices, 0.84, "block BLC06")  # kappa_max = 0.5's interval reaches up to it
    assert "κ_max ≥ 1 keeps the median above 0.84 g" in below
    assert "at κ_max = 0.5 the median, 0.800 g, is below the target but its 95 % interval, 0.750–0.850 g" in below
    clear = design.design_markdown(devices, 0.86, "block BLC06")  # neither interval holds 0.86 g
    assert "κ_max ≥ 1 keeps the median above 0.86 g" in clear and "do not settle" not in clear


def test_the_sweep_carries_the_fit_status_and_a_device_that_never_overturns_meets_the_target():
    """No record overturns the block with κ_max = 2 on any stripe: NaN median, status "no overturning"; it
    meets the target (it is the best device), while "all overturned" meets none."""
    import xarray as xr
    points = []
    for k, m, st in ((0.5, math.nan, "all overturned"), (1.0, 0.9, "ok"), (2.0, math.nan, "no overturning")):
        points.append(xr.Dataset({"fragility_median": ("strategy", [0.6, m]), "fit_status": ("strategy", ["ok", st])},
                                 coords={"strategy": ["FS", "CS01"], "kappa_max": k, "damping_ratio": 0.05},
                                 attrs={"record_suite": "s", "n_records": 3, "compute_time_s": 1.0}))
    devices = design.gather_devices(points)
    assert devices.fit_status.sel(strategy="CS01", damping_ratio=0.05).values.tolist() == [
        "all overturned", "ok", "no overturning"]
    assert design.smallest_kappa(devices, "CS01", 0.05, 0.5) == 1.0
    assert design.smallest_kappa(devices, "CS01", 0.05, 1.5) == 2.0  # before: NaN, "does not reach"
    text = design.design_markdown(devices, 1.5, "block BLC06")
    assert "κ_max ≥ 2 keeps the median above 1.5 g" in text and "never overturns" in text and "nan" not in text
