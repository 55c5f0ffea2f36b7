"""The report's pages (rockstudy.report) and its overview page (workflow/report/workflow.rst)."""
from __future__ import annotations

import math
import pickle
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from rockstudy import report

ROOT = Path(__file__).resolve().parents[1]


def comparison() -> xr.Dataset:
    rows = ["FS vs no_noise", "CS01 vs fs_same_noise"]
    paper = np.array([[-2.01, -5.43, -6.28], [28.02, 30.51, 32.44]])
    ours = np.array([[math.nan, -0.44, math.nan], [math.nan, 40.83, math.nan]])
    return xr.Dataset({"paper": (("row", "noise_level"), paper), "ours": (("row", "noise_level"), ours),
                       "difference": (("row", "noise_level"), ours - paper)},
                      coords={"row": rows, "noise_level": ["R001", "R005", "R010"]})


def claims() -> xr.Dataset:
    return xr.Dataset({"passed": ("claim", np.array([1, 0, -1, 1], dtype=np.int8)),
                       "paper_passed": ("claim", np.array([-1, 1, 0, 1], dtype=np.int8)),
                       "section": ("claim", ["5.1", "5.1", "5.2", "6"]),
                       "statement": ("claim", ["FS < 0 <b>", "CS01 beats CS02", "delay harmless", "range"]),
                       "evidence": ("claim", ["-0.44 %", "x", "n/a", "y"])},
                      coords={"claim": ["a", "b", "c", "d"]})


def test_table1_shows_ours_and_the_paper_in_each_row():
    html = report.table1_beside_paper_html(comparison())
    fs_row = re.search(r"<tr><th>FS vs. no noise</th>(.*?)</tr>", html).group(1)
    assert "-2.01" in fs_row and "-0.44" in fs_row and "+4.99" in fs_row and "40.83" not in fs_row
    assert fs_row.count("–") == 4  # R001 and R010: no number of this run, no difference
    compact = report.table1_compact_html(comparison())
    assert "-0.44 (-5.43)" in compact and "+40.83 (+30.51)" in compact and "– (-2.01)" in compact


def test_claims_verdicts_counts_and_escaping():
    ds = claims()
    assert report.claims_summary(ds) == {"PASS": 2, "FAIL": 1, "n/a": 1}
    html = report.claims_html(ds)
    assert "2 PASS, 1 FAIL, 1 not evaluated" in html
    assert "&lt;b&gt;" in html and "<b>" not in html  # statements are text, not markup
    rows = re.findall(r"<tr><td class=\"num\">(\d+)</td>(.*?)</tr>", html)
    assert [int(i) for i, _ in rows] == [1, 2, 3, 4]
    assert 'class="pass">✓ PASS</span></td><td><span class="na">n/a' in rows[0][1]  # ours PASS, paper n/a
    assert 'class="fail">✗ FAIL</span></td><td><span class="pass">✓ PASS' in rows[1][1]


def test_overview_is_styled_inline():
    html = report.overview_html(comparison(), claims())
    assert "<table style=" in html and "<style" not in html
    assert 'class="pass" style="color: #0b5394' in html and 'class="fail" style="color: #b45309' in html


def test_markdown_page_makes_tables_and_marks_verdicts():
    md = "# Table 1: J_OS\n\n| strategy | R005 |\n|---|---|\n| CS01 | **PASS** |\n| CS02 | **FAIL** |\n"
    page = report.markdown_page(md)
    assert page.startswith("<!DOCTYPE html>") and "<title>Table 1: J_OS</title>" in page
    assert "<table>" in page and "<td>CS01</td>" in page
    assert '<span class="pass">✓ PASS</span>' in page and '<span class="fail">✗ FAIL</span>' in page
    assert "<script" not in report.markdown_page("<script>alert(1)</script>\n")  # raw HTML is not passed through


def test_source_fingerprint_reruns_by_hash_and_reads_by_what_it_covers():
    from rockstudy.core.io import netcdf_attr

    digest = "0123456789abcdef" * 4
    fp = report.SourceFingerprint(digest, "core, model")
    assert repr(fp) == repr(digest) and str(fp) == fp.digest == digest
    assert netcdf_attr(fp) == digest  # a script that stores the parameter in a dataset stores the hash
    assert f"{fp}" == fp.description == f"rockstudy {__import__('rockstudy').__version__} sources: core, model"
    assert digest not in f"{fp}"
    back = pickle.loads(pickle.dumps(fp))  # Snakemake hands params to scripts pickled
    assert back.digest == digest and f"{back}" == f"{fp}"
    assert report.SourceFingerprint("f" * 64, "core, model") != fp


def test_snakemake_sees_the_hash_and_shows_the_words():
    persistence = pytest.importorskip("snakemake.persistence")
    from snakemake.logging import format_dict

    digest = "ab" * 32
    fp = report.SourceFingerprint(digest, "report.py")
    base = getattr(persistence, "PersistenceBase", None) or persistence.Persistence
    serialise = base._serialize_param_builtin  # how a parameter is recorded for the rerun check
    assert serialise(None, fp) == serialise(None, digest)  # results recorded with the bare hash stay valid
    assert serialise(None, report.SourceFingerprint("cd" * 32, "report.py")) != serialise(None, fp)
    shown = format_dict({"library": fp, "n": 3})
    assert shown == "library=rockstudy " + __import__("rockstudy").__version__ + " sources: report.py, n=3"


def test_labels_are_one_column():
    assert report.labels("Thresholds at each T_s", "Fig. 7") == {"result": "Thresholds at each T_s (Fig. 7)"}
    assert report.labels("Fragility") == {"result": "Fragility (beyond the paper)"}


@pytest.mark.parametrize("config", ["config.yaml", ".test/config.yaml"])
def test_overview_page_renders_without_warnings(tmp_path, config):
    """workflow/report/workflow.rst as Snakemake renders it (Jinja with trim_blocks and lstrip_blocks, then
    docutils), for the study's config and the tiny one: no reStructuredText warning, the settings shown."""
    jinja2 = pytest.importorskip("jinja2")
    from docutils.core import publish_parts

    cfg = yaml.safe_load((ROOT / config).read_text())
    cfg["results_dir"] = str(tmp_path)
    (tmp_path / "report").mkdir()
    (tmp_path / "report" / "overview.html").write_text(report.overview_html(comparison(), claims()))
    (tmp_path / "report" / "overview_beyond.html").write_text(report.beyond_overview_html([]))

    class Snakemake:
        config = cfg

    text = jinja2.Environment(trim_blocks=True, lstrip_blocks=True).from_string(
        (ROOT / "workflow" / "report" / "workflow.rst").read_text()).render(snakemake=Snakemake)
    html = publish_parts(text, writer="html", settings_overrides={"halt_level": 2, "report_level": 5})
    body = html["html_body"]
    assert f"seed {cfg['seed']}" in body and "+40.83 (+30.51)" in body
    assert f"for each of {cfg['realisations']} noise realisations" in body
    assert "R005: 5 %" in body and " % of the baseline's energy" in body


def test_one_sign_for_a_change_over_fs():
    """A drop of the probability is negative on every page (overview and risk table alike); FS is the reference."""
    from rockstudy.report import change_over_fs
    assert change_over_fs(51.2) == "−51 %" and change_over_fs(-3.0) == "+3 %" and change_over_fs(0.2) == "0 %"
    assert change_over_fs(40.0, reference=True) == "—" and change_over_fs(float("nan")) == "—"


def test_a_wide_table_is_shown_transposed_on_its_page():
    from rockstudy.report import markdown_page, transposed_wide_tables
    head = "| strategy | " + " | ".join(f"ref: {t}" for t in range(12)) + " |"
    text = "Title\n\n" + head + "\n" + "|---" * 13 + "|\n| CS01 | " + " | ".join(f"{v}%" for v in range(12)) + " |\n"
    out = transposed_wide_tables(text).splitlines()
    assert out[2] == "| strategy → | CS01 |" and out[4] == "| ref: 0 | 0% |" and len(out) == 2 + 2 + 12
    narrow = "| a | b |\n|---|---|\n| 1 | 2 |\n"
    assert transposed_wide_tables(narrow) == narrow
    assert markdown_page(text).count("<tr>") == 13


def stripes_fragility(statuses: dict) -> xr.Dataset:
    """A fragility in PGA over the strategies of ``statuses`` (strategy: fit status): "ok" fits have a median
    of 0.5 g, 0.6 g, ... with a 95 % interval; the others none, as :func:`fit_lognormal_stripes` leaves them."""
    fitted = [status == "ok" for status in statuses.values()]
    median = np.array([0.5 + 0.1 * k if ok else np.nan for k, ok in enumerate(fitted)])
    return xr.Dataset({"fragility_median_physical": ("strategy", median, {"units": "g"}),
                       "median_low_physical": ("strategy", 0.8 * median, {"units": "g"}),
                       "median_high_physical": ("strategy", 1.2 * median, {"units": "g"}),
                       "fragility_median": ("strategy", 4 * median, {"units": "1"}),
                       "fragility_dispersion": ("strategy", np.where(fitted, 0.4, np.nan)),
                       "median_shift_percent": ("strategy", 100 * (median / median[0] - 1)),
                       "fit_status": ("strategy", list(statuses.values()))},
                      coords={"strategy": list(statuses)}, attrs={"record_suite": "test", "n_records": 2})


SCENARIO = {"M7": {"mag": 7, "dist_rup": 10, "v_s30": 400}}


def power_law_site():
    from rockstudy.analysis.hazard import HazardCurve
    x = np.geomspace(0.001, 20.0, 200)
    return {"site": HazardCurve(x, 1e-4 * x ** -2.5, source="power law")}


@pytest.mark.parametrize("sites", ["scenario", "hazard", "both"])
def test_a_risk_table_says_what_each_cell_means(sites):
    """A device that never overturns on the stripes (NaN median, fit status "no overturning") and one that
    overturns on every stripe: their cells say so or carry a footnote that does, no cell is NaN, and the
    sentence on the share from outside the hazard curve is there only with a hazard curve."""
    pytest.importorskip("pygmm")
    from rockstudy.analysis.risk_sites import risk_dataset
    fragility = stripes_fragility({"FS": "ok", "CS01": "no overturning", "CS02": "all overturned", "PASSIVE": "ok"})
    ds = risk_dataset(fragility, scenarios=SCENARIO if sites != "hazard" else None,
                      hazard_curves=power_law_site() if sites != "scenario" else None, years=50)
    table = report.risk_markdown(ds)
    assert not re.search(r"\bnan\b", table, re.IGNORECASE), table
    rows = {line.split(" | ")[0].strip("| "): line.split(" | ") for line in table.splitlines() if line.startswith("| ")}
    assert "never overturns on these stripes" in rows["CS01"][1] and "overturns on every stripe" in rows["CS02"][1]
    for name in ("CS01", "CS02"):
        marks = {cell.strip(" |")[-1] for cell in rows[name][1:]}
        assert len(marks) == 1 and all(cell.strip(" |").startswith("—") for cell in rows[name][2:]), rows[name]
        mark = marks.pop()
        note = next(line for line in table.splitlines() if line.startswith(f"- {mark} {name} "))
        assert "no number is given" in note
    assert "—" not in "".join(rows["PASSIVE"][1:-1]) and "%" in rows["PASSIVE"][-1]
    assert ("outside the curve" in table) == (sites != "scenario")
    overview = report.beyond_overview_html([fragility], [ds])
    assert not re.search(r"\bnan\b", overview, re.IGNORECASE) and "never overturns on these stripes" in overview


def test_a_risk_table_without_any_rate_claims_no_share_from_outside_the_curve():
    """Every strategy never overturns on the stripes, FS too: no rate, so no sentence on where the rates
    come from, and the change over FS of the others points to FS's footnote."""
    from rockstudy.analysis.risk_sites import risk_dataset
    ds = risk_dataset(stripes_fragility({"FS": "no overturning", "CS01": "no overturning"}),
                      hazard_curves=power_law_site(), years=50)
    table = report.risk_markdown(ds)
    assert not re.search(r"\bnan\b", table, re.IGNORECASE), table
    assert "outside the curve" not in table and "- site: hazard curve power law." in table
    assert table.count("never overturns on these stripes") == 2 + 2  # two median cells, two footnotes
