"""HTML pages and Markdown tables of the study for the workflow report (the front door of the tables, as
:mod:`rockstudy.plotting` is of the figures).

The tables are written as netCDF, CSV and Markdown; a Snakemake report shows an HTML result in the
page, a CSV only as a download. One module per concern:

- :mod:`~rockstudy.report.pages`: the Markdown and HTML helpers (a complete page, Markdown tables as HTML,
  verdicts marked, the references of J_OS in the paper's words);
- :mod:`~rockstudy.report.overview`: Table 1 beside the paper, the claims checklist and the overview page's
  headline tables;
- :mod:`~rockstudy.report.fragility_tables`: the Markdown tables of a record set's fragility;
- :mod:`~rockstudy.report.risk_table`: the Markdown table of a record set's risk, and the change over FS;
- :mod:`~rockstudy.report.parameters`: workflow parameters as the report shows them (source fingerprints,
  checked attributes, labels).

Every public name is importable from ``rockstudy.report`` itself; a submodule is imported when one of its
names is first asked for, so that a job which only unpickles its parameters (:mod:`~rockstudy.report.parameters`)
does not load the tables' dependencies (scipy).
"""
from __future__ import annotations

import importlib

_HOMES = {
    "fragility_tables": (
        "RUN_NUMBERS", "fragility_markdown", "run_numbers_csv", "suite_summary_markdown", "threshold_markdown",
    ),
    "overview": (
        "INLINE", "VERDICT_OF_FLAG", "beyond_overview_html", "claims_compact_html", "claims_html",
        "claims_summary", "overview_html", "table1_beside_paper_html", "table1_compact_html",
    ),
    "pages": (
        "REFERENCE_WORDS", "STYLE", "SWEEP_WORDS", "VERDICT_CLASS", "VERDICT_MARK", "WIDE_TABLE_COLUMNS",
        "document", "in_paper_words", "markdown_html", "markdown_page", "scrolling", "settings_text",
        "transposed_wide_tables", "verdict_html",
    ),
    "parameters": (
        "ExpectedAttributes", "SourceFingerprint", "labels",
    ),
    "risk_table": (
        "NO_FIT_NOTES", "NO_FIT_WORDS", "SUPERSCRIPTS", "change_over_fs", "no_median_words", "risk_markdown",
    ),
}
"""The submodule of each public name."""
_HOME_OF = {name: module for module, names in _HOMES.items() for name in names}

__all__ = sorted(_HOME_OF, key=str.lower)


def __getattr__(name: str):
    """A public name, from its submodule (imported on first use)."""
    if name not in _HOME_OF:
        raise AttributeError(f"module 'rockstudy.report' has no attribute {name!r}")
    value = getattr(importlib.import_module(f"rockstudy.report.{_HOME_OF[name]}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
