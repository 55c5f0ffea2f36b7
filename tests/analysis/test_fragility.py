"""The stripes over a record suite on the compiled engine (against one simulate() call per run), the
fragility datasets and their Markdown tables."""
import math

import numpy as np
import pytest

from rockstudy import Anchorage, Control
from rockstudy.analysis.fragility import fragility_dataset, intensity, stripe_outcomes, suite_fragility_dataset
from rockstudy.analysis.record_scan import is_overturned
from rockstudy.engine.outcome import NO_UPLIFT
from rockstudy.engine.simulate import simulate
from rockstudy.model.record_suites import peak_ground_velocity
from rockstudy.model.records import Record
from rockstudy.model.synthetic import synthetic_suite
from rockstudy.report import fragility_markdown


def test_peak_ground_velocity_of_a_sine_cycle():
    """a = A sin(ωt) over one period from rest: v = A/ω (1 − cos ωt), PGV = 2A/ω."""
    omega, amplitude, dt = 2 * math.pi, 3.0, 1e-4
    t = np.arange(0, 1.0 + dt / 2, dt)
    rec = Record("sine", dt, amplitude * np.sin(omega * t))
    assert peak_ground_velocity(rec) == pytest.approx(2 * amplitude / omega, rel=1e-6)


def _simulated_stripes(block, anchorage, controls, records, levels, measure="pga_ratio"):
    """The stripes one :func:`simulate` call at a time: the reference of the compiled stripes."""
    scale = np.asarray(levels)[None, :] / np.array([intensity(r, block, measure) for r in records])[:, None]
    return np.array([[[simulate(block, anchorage, control, rec.motion(float(scale[r, j]))).overturned
                       for j in range(len(levels))] for r, rec in enumerate(records)] for control in controls])


def test_stripes_scale_records_to_the_level_and_match_direct_runs(blc06):
    records = [r for r, _ in synthetic_suite(3, 5)]
    levels = [0.9, 2.0, 4.0]
    controls = [Control("FS"), Control("CS01")]
    outcome, scale = stripe_outcomes(blc06, Anchorage(), controls, records, levels)
    for r, rec in enumerate(records):
        np.testing.assert_allclose(scale[r] * rec.pga / blc06.uplift_acceleration, levels)
    np.testing.assert_array_equal(is_overturned(outcome), _simulated_stripes(blc06, Anchorage(), controls, records,
                                                                             levels))
    assert is_overturned(outcome[:, :, 2]).any()  # the comparison holds overturning runs
    # below the uplift acceleration (PGA < g tan(alpha)) the block never leaves the ground
    assert np.all(outcome[:, :, 0] == NO_UPLIFT)
    outcome_v, scale_v = stripe_outcomes(blc06, Anchorage(), controls[:1], records[:1], levels, measure="pgv_ratio")
    assert scale_v[0, 1] * intensity(records[0], blc06, "pgv_ratio") == pytest.approx(2.0)
    np.testing.assert_array_equal(is_overturned(outcome_v), _simulated_stripes(blc06, Anchorage(), controls[:1],
                                                                               records[:1], levels, "pgv_ratio"))


def test_fragility_dataset_and_table(blc06):
    records = [r for r, _ in synthetic_suite(6, 3)]
    levels = np.arange(1.0, 9.01, 1.0)
    ds = fragility_dataset(blc06, Anchorage(), [Control("FS"), Control("CS01")], records, levels, n_boot=20, seed=2)
    np.testing.assert_allclose(ds.fraction.values, ds.overturned.mean("record").values)
    assert float(ds.median_ratio.sel(strategy="FS")) == 1.0
    assert float(ds.median_shift_percent.sel(strategy="FS")) == 0.0
    assert ds.intensity.attrs["long_name"].endswith("PGA/(g tan(alpha))")
    table = fragility_markdown(ds)
    assert sum(line.startswith("| ") for line in table.splitlines()) == 3 and "| CS01 |" in table
    with pytest.raises(ValueError, match="must include FS"):
        fragility_dataset(blc06, Anchorage(), [Control("CS01")], records, levels)


@pytest.mark.filterwarnings("error::RuntimeWarning")  # no finite bootstrap ratio: a NaN interval, no warning
def test_suite_fragility_names_every_record_and_its_threshold(blc06):
    """Three synthetic records of the suite by name: the dataset carries suite, id, event and station; each
    threshold lies at or below the first overturning stripe and above the last safe one below it; the
    median in g is the ratio times tan(alpha) g / g_n."""
    from rockstudy.model import record_suites
    from rockstudy.model.records import STANDARD_GRAVITY
    entries = [record_suites.load_record(f"synthetic:SYN00{i}") for i in range(3)]
    levels = np.arange(1.0, 5.01, 0.5)
    ds = suite_fragility_dataset(blc06, Anchorage(), [Control("FS"), Control("CS01")], entries, levels,
                                 suite="synthetic", resolution=0.05, n_boot=5, free_time=10.0)
    assert list(ds.record.values) == [f"synthetic:SYN00{i}" for i in range(3)]
    assert set(ds.record_station.values) == {"SYN000", "SYN001", "SYN002"}
    assert all(str(e).startswith("synthetic") for e in ds.record_event.values)
    over = is_overturned(ds.outcome.values)
    for c in range(2):
        for r in range(3):
            thr = float(ds.threshold_intensity.values[c, r])
            if not over[c, r].any():
                assert np.isnan(thr)
                continue
            first = int(np.argmax(over[c, r]))
            assert thr <= levels[first] and (first == 0 or thr > levels[first - 1])
            assert thr - float(ds.last_safe_intensity.values[c, r]) <= 0.05
    np.testing.assert_allclose(ds.fragility_median_physical.values, ds.fragility_median.values
                               * blc06.uplift_acceleration / STANDARD_GRAVITY)
    np.testing.assert_allclose(ds.threshold_pga.values, ds.threshold_scale.values * ds.record_pga.values[None, :])
    # the table shows both fits of the object in g: the stripes' and the records' thresholds'
    from rockstudy.analysis.risk import threshold_fit
    from rockstudy.report import fragility_markdown
    from rockstudy.report.fragility_tables import _num
    table = fragility_markdown(ds)
    assert "records' thresholds' fit" in table
    for s in ("FS", "CS01"):  # (a strategy that no record overturned shows "—")
        fit, d = threshold_fit(ds, s), ds.sel(strategy=s)
        row = (f"| {s} | {_num(d.fragility_median_physical)} ({_num(d.fragility_dispersion, '.2f')}) "
               f"| {_num(fit.median)} ({_num(fit.dispersion, '.2f')}) |")
        assert row in table


def test_tables_show_a_missing_number_as_a_dash(blc06):
    """A strategy without a fit (every number of its row not finite: no record overturned it, say) prints
    "—" in each of its cells in every fragility table, never "nan"; the other rows print as before."""
    from rockstudy.analysis.fragility import suite_summary
    from rockstudy.model import record_suites
    from rockstudy.report import fragility_markdown
    from rockstudy.report.fragility_tables import suite_summary_markdown
    entries = [record_suites.load_record(f"synthetic:SYN00{i}") for i in range(3)]
    ds = suite_fragility_dataset(blc06, Anchorage(), [Control("FS"), Control("CS01")], entries,
                                 np.arange(1.0, 5.01, 0.5), suite="synthetic", resolution=0.05, n_boot=5,
                                 free_time=10.0)
    before = fragility_markdown(ds)
    gone = ds.copy(deep=True)
    for name, var in gone.data_vars.items():
        if "strategy" in var.dims and var.dtype.kind == "f":
            gone[name] = var.where(var.strategy != "CS01")
    tables = fragility_markdown(gone) + suite_summary_markdown(suite_summary([gone]))
    assert "nan" not in tables.lower()
    cs01 = [line for line in tables.splitlines() if "| CS01 |" in line]
    assert len(cs01) == 3 and all(line.count("—") >= 4 for line in cs01)
    fs_row = next(line for line in before.splitlines() if line.startswith("| FS |"))
    assert fs_row in tables
