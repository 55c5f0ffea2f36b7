"""The report's pages in a reader's words: references named as in the paper, parameters summarised,
tables that scroll inside their column, the fragility headline."""
import numpy as np
import xarray as xr

from rockstudy import report


def test_references_read_as_words_in_headers_and_row_names():
    header = "| strategy | no_noise: R005 | fs_same_noise: R005 | continuous_same_noise: 0.01 |"
    words = report.in_paper_words(header)
    assert not any(key in words for key in report.REFERENCE_WORDS)
    assert "R005: J_OS vs. no noise" in words and "R005: J_OS vs. FS at the same noise" in words
    assert "0.01: J_OS vs. continuous control" in words
    assert report.in_paper_words("CS01 vs fs_same_noise") == "CS01 vs. FS at the same noise"
    assert report.in_paper_words("J_OS against delay (§5.2)") == "J_OS against the actuation delay Δτ [s] (§5.2)"


def test_markdown_pages_show_words_and_scrolling_tables():
    page = report.markdown_page("Table 1\n\n| strategy | no_noise: R005 |\n|---|---|\n| FS | -0.44% |\n")
    assert "no_noise" not in page and "J_OS vs. no noise" in page
    assert page.count('<div class="scroll"><table') == page.count("<table") == 1
    assert "div.scroll { overflow-x: auto" in page


def test_expected_attributes_are_a_dict_shown_as_one_line():
    expect = {f"results/spectra/S{i}.nc": {"block_alpha": 0.25, "frequency_ratio": list(range(100))} for i in range(5)}
    wrapped = report.ExpectedAttributes(expect)
    assert wrapped == expect and repr(wrapped) == repr(expect)  # Snakemake's rerun decision is unchanged
    shown = f"expect={wrapped}"
    assert len(shown) < 150 and "spectra/S0.nc" in shown and "2 more" in shown and "{" not in shown
    import pickle
    assert type(pickle.loads(pickle.dumps(wrapped))) is report.ExpectedAttributes


def test_settings_read_as_words():
    text = report.settings_text({"step": 0.0025, "band": None, "level_means": "energy"})
    assert text == "step 0.0025, band none, level means energy"
    assert report.settings_text(3) == "3"


def _fragility(suite, medians):
    strategies = ["FS", "CS01"]
    return xr.Dataset({"fragility_median_physical": ("strategy", np.asarray(medians, float)),
                       "median_shift_percent": ("strategy", 100 * (np.asarray(medians) / medians[0] - 1))},
                      coords={"strategy": strategies}, attrs={"record_suite": suite, "n_records": 44})


def test_the_overview_names_the_fragility_study_with_its_medians():
    page = report.beyond_overview_html([_fragility("p695-far-field", [0.62, 1.019])])
    assert "p695-far-field (44 records)" in page and "0.620 g" in page and "1.019 g (+64 %)" in page
    assert "overflow-x: auto" in page
    assert report.beyond_overview_html([]).startswith("<!--")
