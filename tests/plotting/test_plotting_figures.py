"""What the figures draw, checked on the artists: every legend entry's line can be seen, axis limits
come from the data, labels sit off the curves, text from files is drawn as text."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
import xarray as xr  # noqa: E402
from matplotlib.text import Text  # noqa: E402
from test_plotting import with_map  # noqa: E402

from builders import BLC06, fake_spectrum, two_fragilities  # noqa: E402
from rockstudy import plotting  # noqa: E402
from rockstudy.analysis.spectra import Scenario  # noqa: E402
from rockstudy.model.control import Control  # noqa: E402
from rockstudy.plotting import histories, layout, records, style  # noqa: E402
from rockstudy.studies import datasets  # noqa: E402


@pytest.fixture(scope="module")
def history():
    return datasets.time_history(Scenario(BLC06, control=Control("CS01")), 2.0, 1.3)


def hidden_lines(ax, tol=1e-2):
    """Labelled lines of ``ax`` that a line drawn above them (higher zorder, or the same and later)
    covers: the same data (within ``tol``) and at least as wide, with no gaps in it."""
    lines = [ln for ln in ax.get_lines() if ln.get_label() and not ln.get_label().startswith("_")]
    order = sorted(range(len(lines)), key=lambda i: (lines[i].get_zorder(), i))
    hidden = []
    for rank, i in enumerate(order):
        below = lines[i]
        for j in order[rank + 1:]:
            above = lines[j]
            x0, y0 = np.asarray(below.get_xdata(), float), np.asarray(below.get_ydata(), float)
            x1, y1 = np.asarray(above.get_xdata(), float), np.asarray(above.get_ydata(), float)
            same = x0.shape == x1.shape and np.allclose(x0, x1) and np.allclose(y0, y1, atol=tol, equal_nan=True)
            solid = above.get_linestyle() in ("-", "solid")
            if same and solid and above.get_linewidth() >= below.get_linewidth():
                hidden.append(below.get_label())
    return hidden


def test_every_curve_with_a_legend_entry_shows_beside_the_reference_and_the_others():
    base = np.array([1.2, 1.5, 1.9, 2.6])
    sweeps = [fake_spectrum("CS01", 0.05, base + d, sampling_time=t)
              for t, d in ((0.0025, 0.002), (0.01, 0.004), (0.02, 0.006))]
    fig = plotting.figure_timing(sweeps, "sampling_time", 4.0, "7", [fake_spectrum("CS01", 0.05, base)])
    ax = fig.axes[0]
    labels = ax.get_legend_handles_labels()[1]
    assert sum("ms" in label for label in labels) == 3 and any("reference" in label for label in labels)
    assert hidden_lines(ax) == []
    lines = [ln for ln in ax.get_lines() if "ms" in ln.get_label()]
    widths = [ln.get_linewidth() for ln in lines]
    assert widths == sorted(widths, reverse=True) and len(set(widths)) == 3  # nested: each shows round the next
    reference = next(ln for ln in ax.get_lines() if "reference" in ln.get_label())
    assert reference.get_linewidth() < min(widths) and reference.get_linestyle() != "-"
    plt.close(fig)


def test_the_hidden_line_check_can_fail():
    fig, ax = plt.subplots()
    ax.plot([0, 1], [1, 2], lw=1.0, label="under")
    ax.plot([0, 1], [1, 2], lw=2.0, label="over")
    assert hidden_lines(ax) == ["under"]
    plt.close(fig)


def test_rotation_panel_limits_come_from_the_data_and_the_label_sits_off_the_curves(history):
    spectrum = fake_spectrum("FS", 0.05, np.array([[1.0, 1.4, 2.0, 3.0], [1.0, 1.5, 2.1, 3.0]]))
    point = {"label": "Ex01", "frequency_ratio": 2.0, "amplitude_ratio": 2.05, "a_max0_ratio": 4.0}
    fig = plotting.figure_realisations(spectrum, [history, history], point)
    a, b = fig.axes
    end = b.get_xlim()[1]
    shown = history["rotation_ratio"].where(history["t"] <= end)
    low, high = min(float(shown.min()), -1.0), max(float(shown.max()), 1.0)
    y0, y1 = b.get_ylim()
    assert y0 <= low and y1 >= high  # everything drawn is inside
    assert y1 - y0 <= 1.2 * (high - low)  # and the axis is not much wider than the data
    note = next(t for t in a.texts if t.get_text() == "Ex01")
    renderer = fig.canvas.get_renderer()
    box = Text.get_window_extent(note, renderer)
    for line in a.get_lines():
        x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
        if line.get_label() == "Ex01" or x.size < 2:
            continue
        s = np.linspace(0, 1, 200)
        xs = np.interp(s * (x.size - 1), np.arange(x.size), x)
        ys = np.interp(s * (x.size - 1), np.arange(x.size), y)
        page = line.get_transform().transform(np.column_stack([xs, ys]))
        inside = (page[:, 0] >= box.x0) & (page[:, 0] <= box.x1) & (page[:, 1] >= box.y0) & (page[:, 1] <= box.y1)
        assert not inside.any(), f"the label Ex01 is drawn over {line.get_label()}"
    plt.close(fig)


def test_limits_of_holds_the_values_and_the_guides():
    assert layout.limits_of([[0.0, np.nan, 2.0]], include=(-1.0,), margin=0.0) == (-1.0, 2.0)
    low, high = layout.limits_of([[1.0, 3.0]], margin=0.1)
    assert (low, high) == pytest.approx((0.8, 3.2))


def test_dense_switching_is_found_and_explained(history):
    t = np.r_[np.linspace(0, 1, 11), 1 + np.arange(1, 41) * 1e-3, np.linspace(1.1, 3, 20)]
    k = np.r_[np.zeros(11), np.arange(40) % 2, np.ones(20)]
    bursts = histories.switch_bursts(t, k, end=3.0)
    assert len(bursts) == 1
    t0, t1, n = bursts[0]
    assert t0 == pytest.approx(1.002) and t1 == pytest.approx(1.04) and n == 39
    assert histories.switch_bursts(t, k, end=3.0, min_switches=50) == []
    fig = plotting.figure_control_history(history, "2")
    found = histories.switch_bursts(history["t"].values, history["stiffness_ratio"].values, fig.axes[0].get_xlim()[1])
    notes = [t.get_text() for t in fig.texts]
    assert bool(found) == any("switches" in text for text in notes)
    plt.close(fig)


def test_four_maps_are_a_two_by_two_grid():
    maps = [with_map(fake_spectrum(s, 0.0, [1.0, 1.5, 2.0, 3.0])) for s in ("FS", "PASSIVE", "CS01", "CS02")]
    fig = plotting.figure_maps(maps, 4.0)
    axes = fig.axes
    assert len(axes) == 4
    assert len({round(ax.get_position().x0, 3) for ax in axes}) == 2
    assert len({round(ax.get_position().y0, 3) for ax in axes}) == 2
    width, height = fig.get_size_inches()
    assert width / height < 1.5  # printed 17 cm wide, the tick labels keep most of their size
    plt.close(fig)


def _record_thresholds(events):
    n, strategies = len(events), ["FS", "PASSIVE", "CS01", "CS02"]
    thr = np.full((len(strategies), n), 0.5)  # every strategy at the same PGA: markers would coincide
    return xr.Dataset({"threshold_pga": (("strategy", "record"), thr),
                       "threshold_scale": (("strategy", "record"), thr / 0.3),
                       "record_pga": ("record", np.full(n, 0.3))},
                      coords={"strategy": strategies, "record": np.arange(n),
                              "record_id": ("record", [f"{i}a" for i in range(n)]),
                              "record_event": ("record", events)},
                      attrs={"record_suite": "test $suite"})


def test_record_rows_are_readable_and_markers_of_one_row_do_not_overlap():
    fig = plotting.figure_record_thresholds(_record_thresholds(["Loma Prieta", "Kobe, Japan", "Landers"]))
    ax = fig.axes[0]
    assert all(label.get_fontsize() >= 8 for label in ax.get_yticklabels())
    markers = [ln for ln in ax.get_lines() if ln.get_marker() not in (None, "None", "")]
    points_per_pixel = 72.0 / fig.dpi
    for row in range(3):
        heights = sorted(ln.get_transform().transform((ln.get_xdata()[row], ln.get_ydata()[row]))[1] for ln in markers)
        gaps = np.diff(heights) * points_per_pixel
        assert gaps.min() >= 0.9 * max(ln.get_markersize() for ln in markers), gaps
    plt.close(fig)


def test_a_dollar_in_a_name_from_a_file_is_drawn_as_text(tmp_path):
    assert style.plain_text("a $b") == r"a \$b"
    ds = _record_thresholds(["Loma $_$ Prieta", "cost $5 and $6", "Landers"])  # "$_$" is bad mathtext
    fig = records.figure_record_thresholds(ds)
    plotting.save_figure(fig, tmp_path / "r.png")  # an unescaped "$" fails here, in mathtext
    assert (tmp_path / "r.png").stat().st_size > 1000


def test_simulate_plot_with_a_dollar_in_the_record_name(tmp_path, capsys):
    from rockstudy.cli import main
    from rockstudy.model import records as record_files
    t = np.arange(0, 1.0, 0.01)
    record = record_files.Record("Quake $_$ 1", 0.01, 3.0 * np.sin(2 * np.pi * 2 * t))  # "$_$": bad mathtext
    path = record_files.write_at2(record, tmp_path / "q.AT2")
    assert record_files.read_at2(path).name == "Quake $_$ 1"
    main(["simulate", "--strategy", "CS01", "--record", str(path), "--plot", str(tmp_path / "q.png")])
    assert (tmp_path / "q.png").stat().st_size > 1000


def test_design_charts_build_and_draw_a_dollar_in_the_suite_name_as_text(tmp_path):
    strategies, R, alpha = ["FS", "CS01", "CS02"], [0.5, 1.0], [0.2, 0.3]
    rng = np.random.default_rng(1)
    medians = np.array([0.4, 0.8, 0.9])[:, None, None] + rng.uniform(0, 0.2, (3, 2, 2))  # FS lowest
    blocks = xr.Dataset({"jos": (("strategy", "R", "alpha"), rng.uniform(0, 80, (3, 2, 2))),
                         "fragility_median": (("strategy", "R", "alpha"), medians)},
                        coords={"strategy": strategies, "R": R, "alpha": alpha},
                        attrs={"record_suite": "suite $_$ x"})  # "$_$": bad mathtext unless escaped
    devices = xr.Dataset({"fragility_median": (("strategy", "kappa_max", "damping_ratio"),
                                               rng.uniform(0.3, 1.5, (3, 2, 2)))},
                         coords={"strategy": strategies, "kappa_max": [0.5, 1.0], "damping_ratio": [0.02, 0.05]},
                         attrs={"record_suite": "suite $_$ x"})
    figures = [plotting.figure_design_jos_maps(blocks), plotting.figure_design_winner(blocks),
               plotting.figure_design_size_effect(blocks), plotting.figure_design_devices(devices, 1.0)]
    for i, fig in enumerate(figures):
        plotting.save_figure(fig, tmp_path / f"d{i}.png")
        assert (tmp_path / f"d{i}.png").stat().st_size > 1000


def test_a_long_record_set_is_drawn_in_two_columns_that_keep_every_record():
    events = [f"Quake {i}" for i in range(44)]
    fig = plotting.figure_record_thresholds(_record_thresholds(events))
    assert len(fig.axes) == 2 and fig.get_size_inches()[1] < 9  # not 44 rows in one tall column
    labels = [t.get_text() for ax in fig.axes for t in ax.get_yticklabels()]
    assert sorted(labels) == sorted(f"{i}a Quake {i}" for i in range(44))
    plt.close(fig)
    assert len(plotting.figure_record_thresholds(_record_thresholds(events[:3])).axes) == 1
    plt.close("all")


def test_a_saved_png_states_its_smallest_text(tmp_path):
    from PIL import Image

    from rockstudy.plotting.save import SMALLEST_TEXT_KEY
    fig, ax = plt.subplots()
    ax.plot([0, 1])
    ax.set_title("small", fontsize=6)
    plotting.save_figure(fig, tmp_path / "f.png")
    assert float(Image.open(tmp_path / "f.png").text[SMALLEST_TEXT_KEY]) == pytest.approx(6 * 150 / 72, abs=0.01)


def test_the_risk_figure_with_a_hazard_curve_is_as_wide_as_without():
    """Three panels on two rows: a page that fits the figure to its width draws it at the two-panel scale."""
    pytest.importorskip("pygmm")
    from rockstudy.analysis.hazard import HazardCurve
    from rockstudy.analysis.risk_sites import risk_dataset
    from rockstudy.plotting.risk import figure_risk
    fragility = two_fragilities()
    x = np.geomspace(0.001, 20.0, 100)
    scenario = {"M7": {"mag": 7, "dist_rup": 10, "v_s30": 400}}
    with_hazard = figure_risk(risk_dataset(fragility, scenarios=scenario,
                                           hazard_curves={"site": HazardCurve(x, 1e-4 * x ** -2.5, source="law")}))
    without = figure_risk(risk_dataset(fragility, scenarios=scenario))
    assert len(with_hazard.axes) == 3 and len(without.axes) == 2
    assert with_hazard.get_size_inches()[0] == without.get_size_inches()[0]
    plt.close("all")
