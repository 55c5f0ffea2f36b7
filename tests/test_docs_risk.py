"""docs/risk.md as a user meets it: every Python block in order in one namespace, then every `rockstudy`
command (they read the files the blocks wrote)."""
import json

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
    fragility, free, held, scenario, target = outputs
    assert fragility["median_g"] > 0 and free["strategy"] == "FS" and held["strategy"] == "CS01"
    # the command line gives the library's numbers for the same fragility file and site
    for out in (free, held):
        fit = risk.fragility_from_dataset(io.read_netcdf("cs01.nc"), out["strategy"])
        assert out["annual_rate"] == risk.annual_rate(fit, namespace["site"]).annual_rate
    assert scenario["gmm"] == "BSSA14" and 0 < scenario["probability"] < 1
    assert target["median_g"] == namespace["needed"]
