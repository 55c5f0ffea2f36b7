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

Every public name is importable from ``rockstudy.report`` itself.
"""
from rockstudy.report.fragility_tables import (
    RUN_NUMBERS,
    fragility_markdown,
    run_numbers_csv,
    suite_summary_markdown,
    threshold_markdown,
)
from rockstudy.report.overview import (
    INLINE,
    VERDICT_OF_FLAG,
    beyond_overview_html,
    claims_compact_html,
    claims_html,
    claims_summary,
    overview_html,
    table1_beside_paper_html,
    table1_compact_html,
)
from rockstudy.report.pages import (
    REFERENCE_WORDS,
    STYLE,
    SWEEP_WORDS,
    VERDICT_CLASS,
    VERDICT_MARK,
    WIDE_TABLE_COLUMNS,
    document,
    in_paper_words,
    markdown_html,
    markdown_page,
    scrolling,
    settings_text,
    transposed_wide_tables,
    verdict_html,
)
from rockstudy.report.parameters import (
    ExpectedAttributes,
    SourceFingerprint,
    labels,
)
from rockstudy.report.risk_table import (
    NO_FIT_NOTES,
    NO_FIT_WORDS,
    SUPERSCRIPTS,
    change_over_fs,
    no_median_words,
    risk_markdown,
)

__all__ = [
    "beyond_overview_html", "change_over_fs", "claims_compact_html", "claims_html", "claims_summary", "document",
    "ExpectedAttributes", "fragility_markdown", "in_paper_words", "INLINE", "labels", "markdown_html",
    "markdown_page", "NO_FIT_NOTES", "NO_FIT_WORDS", "no_median_words", "overview_html", "REFERENCE_WORDS",
    "risk_markdown", "RUN_NUMBERS", "run_numbers_csv", "scrolling", "settings_text", "SourceFingerprint", "STYLE",
    "suite_summary_markdown", "SUPERSCRIPTS", "SWEEP_WORDS", "table1_beside_paper_html", "table1_compact_html",
    "threshold_markdown", "transposed_wide_tables", "VERDICT_CLASS", "verdict_html", "VERDICT_MARK",
    "VERDICT_OF_FLAG", "WIDE_TABLE_COLUMNS",
]
