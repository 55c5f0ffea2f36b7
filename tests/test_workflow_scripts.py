"""The workflow's scripts run outside Snakemake: each has ``main(snakemake)``, called here with a stand-in
object on small inputs. A step refuses an input that is not what its rule expects (a swapped record set,
a design point copied over another, a gathered sweep with a row dropped), naming the file."""
import importlib.util
import shutil

import numpy as np
import pytest
import xarray as xr

from builders import BLC06, FREQS, fake_spectrum
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario
from rockstudy.core import io
from rockstudy.model.control import Control
from rockstudy.studies import datasets, expectations, tables
from workflow_runs import ROOT

SCRIPTS = ROOT / "workflow" / "scripts"


def script(name: str):
    """The workflow script ``name`` as a module (its ``main`` not yet called)."""
    spec = importlib.util.spec_from_file_location(f"workflow_script_{name}", SCRIPTS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class Files(list):
    """A list of file names with names for some of them, like Snakemake's ``input`` and ``output``."""

    def __init__(self, files=(), **named):
        super().__init__([str(f) for f in files] + [str(f) for f in named.values() if not isinstance(f, list)])
        for key, value in named.items():
            setattr(self, key, [str(f) for f in value] if isinstance(value, list) else str(value))


class StandIn:
    """The attributes of the object Snakemake gives a script."""

    def __init__(self, tmp_path, input=(), output=(), params=None, wildcards=None):
        self.input = input if isinstance(input, Files) else Files(input)
        self.output = output if isinstance(output, Files) else Files(output)
        self.params = type("Params", (), params or {})()
        self.wildcards = type("Wildcards", (), wildcards or {})()
        self.log = [str(tmp_path / "job.log")]
        self.threads = 1


def test_every_script_has_a_main_and_runs_nothing_on_import():
    names = sorted(p.stem for p in SCRIPTS.glob("*.py"))
    assert len(names) >= 38
    for name in names:
        assert callable(script(name).main), name


def _spectra(tmp_path, levels):
    """Fake spectra of FS, CS01, CS02 at ``levels`` written to files, with their expectations."""
    paths, expect = [], {}
    for i, strategy in enumerate(("FS", "CS01", "CS02")):
        for name, value in levels.items():
            ds = datasets.gather_spectra([fake_spectrum(strategy, value, np.full((2, 4), 1.5 + value + 0.1 * i))])
            path = io.write_netcdf(ds, tmp_path / f"{strategy}_{name}.nc")
            paths.append(path)
            expect[str(path)] = datasets.expected_attrs(
                Scenario(BLC06, control=Control(strategy), noise_level=value), realisations=[0, 1],
                frequency_ratios=FREQS, amplitude_grid=AmplitudeGrid())
    return paths, expect


def test_table1_main_writes_the_table_of_its_spectra_and_refuses_a_swapped_one(tmp_path):
    levels = {"R000": 0.0, "R005": 0.05}
    paths, expect = _spectra(tmp_path, levels)
    out = Files(nc=tmp_path / "t.nc", csv=tmp_path / "t.csv", md=tmp_path / "t.md")
    params = {"expect": expect, "strategies": ["FS", "CS01", "CS02"], "noise_levels": levels, "a_max0": 1.0}
    script("table1").main(StandIn(tmp_path, paths, out, params))
    table = io.read_netcdf(out.nc)
    direct = tables.table1([io.read_netcdf(p) for p in paths], ["FS", "CS01", "CS02"], levels, 1.0)
    np.testing.assert_array_equal(table["j_os"].values, direct["j_os"].values)
    assert "J_OS" in (tmp_path / "t.md").read_text() and (tmp_path / "job.log").exists()
    shutil.copyfile(paths[2], paths[0])  # CS01 without noise copied over FS without noise
    with pytest.raises(ValueError, match=rf"{paths[0]}: control_strategy is 'CS01', expected 'FS'"):
        script("table1").main(StandIn(tmp_path, paths, out, params))


def test_convergence_main_and_an_edited_threshold(tmp_path):
    (path, *_), expect = _spectra(tmp_path, {"R005": 0.05})
    out = tmp_path / "conv.nc"
    params = {"expect": {str(path): expect[str(path)]}}
    script("convergence").main(StandIn(tmp_path, [path], [out], params))
    conv = io.read_netcdf(out)
    np.testing.assert_array_equal(conv["threshold_convergence"].values[-1], io.read_netcdf(path)["threshold"].values)
    edited = io.read_netcdf(path)
    edited["threshold"] = edited["threshold"] * 1.5  # the attributes kept
    edited["threshold"].attrs = io.read_netcdf(path)["threshold"].attrs
    io.write_netcdf(edited, path)
    with pytest.raises(ValueError, match=rf"{path}: threshold is not the lowest threshold_realisation"):
        script("convergence").main(StandIn(tmp_path, [path], [out], params))


def test_gather_main_gathers_its_chunks(tmp_path):
    sc = Scenario(BLC06, control=Control("CS01"), noise_level=0.05)
    paths, expect = [], {}
    for k in (0, 1):
        path = io.write_netcdf(fake_spectrum("CS01", 0.05, [np.full(4, 1.5 + k)], [k]), tmp_path / f"c{k}.nc")
        paths.append(path)
        expect[str(path)] = datasets.expected_attrs(sc, realisations=[k], frequency_ratios=FREQS,
                                                    amplitude_grid=AmplitudeGrid())
    out = tmp_path / "gathered.nc"
    script("gather_spectra").main(StandIn(tmp_path, paths, [out], {"expect": expect, "realisations": [0, 1]}))
    np.testing.assert_array_equal(io.read_netcdf(out)["threshold"].values, np.full(4, 1.5))
    shutil.copyfile(paths[0], paths[1])  # a chunk copied over the other
    with pytest.raises(ValueError, match=rf"{paths[1]}: realisation is \[0\], expected \[1\]"):
        script("gather_spectra").main(StandIn(tmp_path, paths, [out], {"expect": expect, "realisations": [0, 1]}))


def test_html_table_main(tmp_path):
    md = tmp_path / "t.md"
    md.write_text("| a | b |\n|---|---|\n| 1 | 2 |\n")
    script("html_table").main(StandIn(tmp_path, [md], [tmp_path / "t.html"]))
    assert "<table" in (tmp_path / "t.html").read_text()


def test_a_record_set_copied_over_another_stops_the_fragility_step(tmp_path):
    """The fragility job reads its record set first: a set copied over another is refused, naming the file
    and record_set, before any simulation (a wrong fragility median otherwise)."""
    expect = expectations.StudyExpectations({"noise_levels": {"R000": 0.0}})
    sets = {"p695-far-field": "p695-far-field", "p695-near-field-pulse": "p695-near-field-pulse"}
    paths = {}
    for name, members in sets.items():
        paths[name] = tmp_path / f"{name}.nc"
        script("record_set").main(StandIn(tmp_path, [], [paths[name]], {"members": members, "synthetic": None,
                                                                         "library": "abc"},
                                          {"recordset": name}))
        assert io.read_netcdf(paths[name]).attrs["record_set"] == name
    shutil.copyfile(paths["p695-far-field"], paths["p695-near-field-pulse"])
    target = "p695-near-field-pulse"
    job = StandIn(tmp_path, Files(records=paths[target]), [], {
        "expect": {str(paths[target]): expect.record_set(target, sets[target])}}, {"recordset": target})
    with pytest.raises(ValueError, match=rf"{paths[target]}: record_set is 'p695-far-field', expected "
                                         rf"'{target}'"):
        script("fragility").main(job)


def _block_point(R, alpha):
    """The layout of a design block point (rockstudy.studies.design.block_point) without its simulations."""
    return xr.Dataset({"jos": ("strategy", [0.0, 10.0 * R], {"units": "percent"}),
                       "fragility_median": ("strategy", [0.3, 0.4 + R], {"units": "1"})},
                      coords={"strategy": ["FS", "CS01"], "R": ((), float(R)), "alpha": ((), float(alpha))},
                      attrs={"excitation": "modulated", "a_max0_g": 1.0, "record_suite": "steps", "n_records": 2,
                             "rockstudy_version": "0", "compute_time_s": 1.0, "pga_levels_g": [0.1, 0.2]})


def _device_point(kappa, xi):
    return xr.Dataset({"fragility_median": ("strategy", [0.3, 0.4 + kappa], {"units": "1"})},
                      coords={"strategy": ["FS", "CS01"], "kappa_max": ((), float(kappa)),
                              "damping_ratio": ((), float(xi))},
                      attrs={"record_suite": "steps", "n_records": 2, "compute_time_s": 1.0,
                             "pga_levels_g": [0.1, 0.2], **BLC06.to_attrs()})


def test_a_design_point_copied_over_another_stops_the_gather(tmp_path):
    """Copied over another, a design point would silently drop a row of the sweep: the gather refuses it,
    naming the file and R; and the figures refuse a gathered sweep with a row dropped."""
    config = {"block": {"preset": "BLC06"}, "excitation": "modulated", "noise_levels": {"R000": 0.0},
              "design": {"suite": "steps", "strategies": ["FS", "CS01"],
                         "pga_levels_g": {"start": 0.1, "stop": 0.2, "count": 2},
                         "blocks": {"R": [0.5, 1.0], "alpha": [0.2], "a_max0": 1.0},
                         "devices": {"kappa_max": [1.0], "damping_ratio": [0.05]}}}
    expect = expectations.StudyExpectations(config)
    blocks = {(R, 0.2): io.write_netcdf(_block_point(R, 0.2), tmp_path / f"R{R:g}.nc") for R in (0.5, 1.0)}
    device = io.write_netcdf(_device_point(1.0, 0.05), tmp_path / "k1.nc")
    params = {"expect": {**{str(p): expect.design_block(*key) for key, p in blocks.items()},
                         str(device): expect.design_device(1.0, 0.05)},
              "block": {"preset": "BLC06"}, "target": 0.35}
    out = Files(blocks=tmp_path / "blocks.nc", devices=tmp_path / "devices.nc", md=tmp_path / "d.md")
    inputs = Files(blocks=[str(p) for p in blocks.values()], devices=[str(device)])
    script("design_gather").main(StandIn(tmp_path, inputs, out, params))
    gathered = io.read_netcdf(out.blocks)
    assert gathered["R"].values.tolist() == [0.5, 1.0]
    figures = {str(out.blocks): expect.design_blocks(), str(out.devices): expect.design_devices()}
    io.write_netcdf(gathered.isel(R=[0]), out.blocks)  # a row dropped
    with pytest.raises(ValueError, match=rf"{out.blocks}: R is \[0.5\], expected \[0.5, 1.0\]"):
        script("design_figures").main(StandIn(tmp_path, Files(blocks=out.blocks, devices=out.devices), Files(),
                                              {"expect": figures, "target": 0.35}))
    shutil.copyfile(blocks[(0.5, 0.2)], blocks[(1.0, 0.2)])
    with pytest.raises(ValueError, match=rf"{blocks[(1.0, 0.2)]}: R is 0.5, expected 1.0"):
        script("design_gather").main(StandIn(tmp_path, inputs, out, params))
