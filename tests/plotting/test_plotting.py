"""Tests for rockstudy.plotting: axis functions return their artists, figures build and save."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from builders import BLC06, fake_spectrum  # noqa: E402
from rockstudy import plotting  # noqa: E402
from rockstudy.analysis.spectra import OUTCOME_MEANINGS, Scenario  # noqa: E402
from rockstudy.model.control import Control  # noqa: E402
from rockstudy.studies import datasets  # noqa: E402


@pytest.fixture(scope="module")
def history():
    return datasets.time_history(Scenario(BLC06, control=Control("CS01")), 2.0, 1.3)


def with_map(ds):
    amps = np.array([1.0, 2.0, 3.0])
    out = np.zeros((ds.sizes["realisation"], ds.sizes["frequency_ratio"], 3), dtype=np.int8)
    out[..., 1:] = [1, 3]
    ds = ds.assign_coords(amplitude_ratio=amps)
    ds["outcome"] = (("realisation", "frequency_ratio", "amplitude_ratio"), out,
                     {"flag_meanings": " ".join(OUTCOME_MEANINGS)})
    return ds


def test_axis_functions_return_artists(history):
    fig, ax = plt.subplots()
    line = plotting.plot_threshold(ax, fake_spectrum("FS", 0.0, [1.0, np.nan, 2.0, 3.0])["threshold"])
    assert isinstance(line, matplotlib.lines.Line2D) and np.isnan(line.get_ydata()[1])
    assert plotting.plot_a_max0(ax, 4.0).get_ydata()[0] == 4.0
    assert len(plotting.plot_history(ax, history)) == 3
    assert plotting.plot_stiffness(ax, history).get_label() == r"$K/K_{max}$"
    mesh, handles = plotting.plot_outcome_map(ax, with_map(fake_spectrum("FS", 0.0, [1.0, 1.5, 2.0, 3.0])))
    assert len(handles) == len(OUTCOME_MEANINGS) and mesh.get_array().size == 12
    plotting.spectrum_axes(ax, "t")
    assert "omega_p/p" in ax.get_xlabel() and "tan" in ax.get_ylabel()
    plt.close(fig)


def test_figures_build_and_save(tmp_path, history):
    spectra = [fake_spectrum(s, lev, np.full((2, 4), 1.0 + lev * 10)) for s in ("FS", "CS01", "CS02")
               for lev in (0.0, 0.05)]
    conv = datasets.convergence_dataset(spectra[1])
    figs = [plotting.figure_control_history(history, "2"),
            plotting.figure_noise_sensitivity(conv, spectra, 4.0),
            plotting.figure_timing([fake_spectrum("CS01", 0.05, np.ones(4), sampling_time=t) for t in (0.01, 0.1)],
                                   "sampling_time", 4.0, "7"),
            plotting.figure_maps([with_map(spectra[0]), with_map(spectra[2])], 4.0),
            plotting.figure_realisations(spectra[1], [history, history],
                                         {"label": "Ex01", "frequency_ratio": 2.0, "amplitude_ratio": 1.3,
                                          "a_max0_ratio": 4.0})]
    noise = datasets.noise_dataset(Scenario(BLC06, noise_level=0.1), [1.0], [0], 1.0, 1)
    figs.append(plotting.figure_excitation(noise))
    for i, fig in enumerate(figs):
        written = plotting.save_figure(fig, tmp_path / f"f{i}.png", tmp_path / f"f{i}.pdf")
        assert all(p.stat().st_size > 1000 for p in written)
    assert not list(tmp_path.glob("*.part")) and not plt.get_fignums()


def test_no_overturning_up_to_the_bound_is_marked_at_the_top():
    import xarray as xr
    thr = xr.DataArray([1.5, np.nan, 2.0, np.nan], dims="frequency_ratio",
                       coords={"frequency_ratio": [1.0, 2.0, 3.0, 4.0]})
    fig, ax = plt.subplots()
    line = plotting.plot_threshold(ax, thr, color="tab:green")
    markers = [ln for ln in ax.get_lines() if ln is not line]
    assert len(markers) == 1 and markers[0].get_marker() == "^"
    assert list(markers[0].get_xdata()) == [2.0, 4.0] and markers[0].get_color() == "tab:green"
    fig2, ax2 = plt.subplots()
    plotting.plot_threshold(ax2, thr, mark_above=False)
    assert len(ax2.get_lines()) == 1
    plt.close(fig)
    plt.close(fig2)


def _threshold(values):
    import xarray as xr
    return xr.DataArray(np.asarray(values, float), dims="frequency_ratio",
                        coords={"frequency_ratio": [1.0, 2.0, 3.0]})


def test_curves_that_coincide_share_one_legend_entry_and_the_reference_is_on_top():
    fig, ax = plt.subplots()
    lines = plotting.plot_threshold_family(
        ax, [("2.5 ms", _threshold([1.0, 2.0, np.nan])), ("60 ms", _threshold([1.0, 2.5, 3.0]))],
        prefix="d = ", reference=("0", _threshold([1.0, 2.0, np.nan])), suffix=", reference")
    labels = [line.get_label() for line in lines]
    assert labels == ["d = 60 ms", "d = 0 = 2.5 ms, reference"]
    ref = lines[-1]
    assert ref.get_color() == plotting.OKABE_ITO["black"]
    assert ref.get_zorder() > max(line.get_zorder() for line in lines[:-1])
    assert ref.get_linewidth() < lines[0].get_linewidth()  # the wider curve shows around it
    # nearly equal is not equal: two entries
    fig2, ax2 = plt.subplots()
    two = plotting.plot_threshold_family(ax2, [("a", _threshold([1.0, 2.0, 3.0])),
                                               ("b", _threshold([1.0, 2.0, 3.0001]))])
    assert [line.get_label() for line in two] == ["a", "b"]
    plt.close(fig)
    plt.close(fig2)


def test_figures_use_the_colour_blind_safe_palette_and_say_what_they_show(history):
    spectra = [fake_spectrum("CS01", 0.05, np.ones(4), sampling_time=t) for t in (0.01, 0.1)]
    refs = [fake_spectrum("CS01", 0.05, np.ones(4))]
    fig = plotting.figure_timing(spectra, "sampling_time", 4.0, "7", refs)
    ax = fig.axes[0]
    labels = ax.get_legend_handles_labels()[1]
    assert r"$T_s$ = 0 (continuous) = 10 ms = 100 ms, reference" in labels  # identical data: one entry
    assert "Fig." not in fig._suptitle.get_text() and "sampling times" in fig._suptitle.get_text()
    allowed = {matplotlib.colors.to_hex(c) for c in plotting.OKABE_ITO.values()}
    for line in ax.get_lines():
        colour = matplotlib.colors.to_hex(line.get_color())
        grey = len({colour[1:3], colour[3:5], colour[5:7]}) == 1
        assert colour.upper() in {c.upper() for c in allowed} or grey, colour
    plt.close(fig)
    fig = plotting.figure_control_history(history, "2")
    assert "Fig." not in fig.axes[0].get_title() and "CS01" in fig.axes[0].get_title()
    plt.close(fig)


def test_history_velocity_line_shows_the_jump_at_each_impact(history):
    t, v = plotting.velocity_with_impacts(history)
    assert len(t) == history.sizes["t"] + history.sizes["impact"] and np.all(np.diff(t) >= 0)
    i = int(np.searchsorted(t, float(history["impact_time"][0])))
    assert v[i] == float(history["velocity_before_impact_ratio"][0])
    assert v[i + 1] == float(history["velocity_after_impact_ratio"][0])


def test_outcome_map_has_no_red_against_green():
    safe = matplotlib.colors.to_rgb(plotting.OUTCOME_COLOURS["safe"])
    assert safe[2] > safe[1] > safe[0]  # blue, not green
    for name in ("overturned_without_impact", "overturned_after_impact"):
        red, green, blue = matplotlib.colors.to_rgb(plotting.OUTCOME_COLOURS[name])
        assert red > green > blue  # vermillion / orange


def test_pga_in_g_axis_converts_with_tan_alpha():
    fig, ax = plt.subplots()
    ax.set_xlim(0, 4)
    sec = plotting.pga_in_g_axis(ax, 0.25)
    forward, inverse = sec._functions
    assert forward(4.0) == pytest.approx(1.0) and inverse(1.0) == pytest.approx(4.0)
    assert sec.get_xlabel() == "PGA [g]"
    with pytest.raises(ValueError, match="tan_alpha"):
        plotting.pga_in_g_axis(ax, 0.0)
    plt.close(fig)


def test_a_figure_saves_to_the_same_bytes_twice(tmp_path):
    spectra = [fake_spectrum("CS01", 0.05, np.ones(4), sampling_time=t) for t in (0.01, 0.1)]
    for name in ("a", "b"):
        plotting.save_figure(plotting.figure_timing(spectra, "sampling_time", 4.0, "7"), tmp_path / f"{name}.png",
                             tmp_path / f"{name}.pdf")
    for suffix in ("png", "pdf"):
        assert (tmp_path / f"a.{suffix}").read_bytes() == (tmp_path / f"b.{suffix}").read_bytes(), suffix


@pytest.mark.parametrize("n_panels", [1, 4])
def test_probability_colour_bar_stays_inside_the_figure(n_panels):
    """With one panel the colour bar and its label used to fall off the right edge."""
    from rockstudy.analysis.probability import probability_surface
    from rockstudy.analysis.spectra import AmplitudeGrid
    surface = probability_surface(Scenario(BLC06, control=Control("FS"), noise_level=0.05), [1.0, 2.0],
                                  realisations=range(2), grid=AmplitudeGrid(start=0.9, stop=2.7, step=0.6,
                                                                            resolution=0.1))
    surfaces = [surface.assign_coords(strategy=s) for s in ("FS", "PASSIVE", "CS01", "CS02")[:n_panels]]
    fig = plotting.figure_probability(surfaces, 4.0)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    bar = next(ax for ax in fig.axes if ax.get_ylabel().startswith("P(overturn)"))
    inside = fig.bbox.padded(1.0)
    for ax in fig.axes:
        box = ax.get_tightbbox(renderer)
        assert inside.x0 <= box.x0 and box.x1 <= inside.x1 and inside.y0 <= box.y0 and box.y1 <= inside.y1, ax
    assert bar.get_position().x0 > max(ax.get_position().x1 for ax in fig.axes if ax is not bar)
    plt.close(fig)
