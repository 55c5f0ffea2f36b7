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
