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
