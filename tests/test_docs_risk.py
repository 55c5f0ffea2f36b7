"""docs/risk.md as a user meets it: every Python block in order in one namespace, then every `rockstudy`
command (they read the files the blocks wrote)."""
import json

import pytest

from rockstudy.analysis import risk
from rockstudy.cli import main
from rockstudy.core import io
from test_docs import DOCS, commands, run_python_blocks


def test_risk_page_examples_run(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    namespace = run_python_blocks(DOCS / "risk.md", "risk_page")
    printed = capsys.readouterr().out
    assert "% in 50 years" in printed and "the device lowers the rate by" in printed
    outputs = []
    for args in commands(DOCS / "risk.md"):
        assert main(args) == 0, args
        outputs.append(json.loads(capsys.readouterr().out))
    fragility, free, held, scenario, target, bay = outputs
    assert fragility["median_g"] > 0 and free["strategy"] == "FS" and held["strategy"] == "CS01"
    # the command line gives the library's numbers for the same fragility file and site
    for out in (free, held):
        fit = risk.fragility_from_dataset(io.read_netcdf("cs01.nc"), out["strategy"])
        assert out["annual_rate"] == risk.annual_rate(fit, namespace["site"]).annual_rate
    assert scenario["gmm"] == "BSSA14" and 0 < scenario["probability"] < 1
    assert target["median_g"] == namespace["needed"] and target["extrapolated"] is False
    # the OpenQuake excerpt: two sites, their coordinates, the library's numbers, the hand conversion
    assert [(b["lon"], b["lat"]) for b in bay["sites"]] == [(-122.34, 37.72), (-122.15, 37.56)]
    probability = namespace["at_sites"].probability.sel(strategy="FS").values
    for entry, expected in zip(bay["sites"], [risk.annual_rate(risk.LognormalFragility(0.3, 0.4), s.curve).annual_rate
                                              for s in namespace["bay"].values()]):
        assert entry["annual_rate"] == expected and 0 <= entry["probability"] <= 1
    first = next(iter(namespace["bay"].values())).curve
    assert first.annual_rate[0] == pytest.approx(2.0046e-3, rel=1e-4)  # the page's hand conversion
    assert probability.shape == (2,)
