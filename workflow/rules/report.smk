# The report as a study: HTML pages of the tables (a Snakemake report shows an HTML result in the page,
# a CSV only as a download) and the headline fragment of the overview page (workflow/report/workflow.rst).
# Every page is made from a table the study already wrote; nothing here computes a result.

REPORT_DIR = f"{OUT}/report"
OVERVIEW = f"{REPORT_DIR}/overview.html"
"""Table 1 beside the paper and the claims checklist, included in the report's overview page."""


# Markdown tables of the study -> HTML pages: (markdown, caption, category, subcategory, what it shows, paper)
HTML_TABLES = {
    "table1": (f"{OUT}/tables/table1.md", "table1.rst", "Tables", "J_OS",
               "Table 1: J_OS of each strategy against no noise and against FS", "Table 1"),
    "timing_sampling": (f"{OUT}/tables/timing_sampling.md", "timing_sampling.rst", "Tables", "J_OS",
                        "J_OS under sampled control, each sampling time T_s", "§5.2, Fig. 7"),
    "timing_delay": (f"{OUT}/tables/timing_delay.md", "timing_delay.rst", "Tables", "J_OS",
                     "J_OS under delayed control, each delay", "§5.2, Fig. 8"),
}
if BEYOND:
    HTML_TABLES["fragility_summary"] = (f"{OUT}/tables/fragility_summary.md", "fragility_summary.rst", "Tables",
                                        "Fragility", "Fragility medians of every strategy on every record set", "")
    for name in RECORD_SETS:
        HTML_TABLES[f"fragility_{name}"] = (f"{OUT}/tables/fragility_{name}.md", "fragility_table.rst", "Tables",
                                            "Fragility", f"Fragility on {name}: medians, dispersions, shift over FS",
                                            "")
        HTML_TABLES[f"record_thresholds_{name}"] = (
            f"{OUT}/tables/record_thresholds_{name}.md", "record_thresholds_table.rst", "Tables", "Fragility",
            f"Smallest overturning scale of each record of {name}, per strategy", "")
if BEYOND and config.get("risk"):
    for name in RECORD_SETS:
        HTML_TABLES[f"risk_{name}"] = (f"{OUT}/tables/risk_{name}.md", "risk_table.rst", "Tables", "Risk",
                                       f"Risk of overturning per strategy at a site, {name}", "")
# Pages of the studies outside `all` (targets `reproduction`, `calibration`): one rule each, so that
# `all` does not ask for them.
EXTRA_HTML_TABLES = {
    "readings": (f"{OUT}/reproduction/readings/readings.md", "readings.rst", "Reproduction", "Noise readings",
                 "FS row of Table 1 under each reading of the noise model", "§5, Table 1"),
    "calibration": (f"{OUT}/reproduction/calibration/calibration.md", "calibration_table.rst", "Reproduction",
                    "Device calibration", "Device calibration: every screened anchorage and the best", "Table 1"),
}


# The report entry of each HTML page made from a Markdown table: (markdown, caption, category, subcategory,
# what it shows, paper) -> report(<markdown>.html, ...)
HTML_PAGES = {key: report(md.removesuffix(".md") + ".html", caption=f"../report/{caption}", category=category,
                          subcategory=subcategory, labels=report_pages.labels(shows, paper))
              for key, (md, caption, category, subcategory, shows, paper)
              in {**HTML_TABLES, **EXTRA_HTML_TABLES}.items()}


for key, entry in EXTRA_HTML_TABLES.items():

    rule:
        name:
            f"html_{key}"
        input:
            entry[0],
        output:
            HTML_PAGES[key],
        log:
            f"{OUT}/logs/report/html_{key}.log",
        params:
            pages=REPORT_CODE,
        localrule: True
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/html_table.py"


OVERVIEW_BEYOND = f"{REPORT_DIR}/overview_beyond.html"
"""The headline numbers of the studies beyond the paper in `all` (the fragility medians), for the overview page."""


BEYOND_PAGES_READ = ([("fragility", name) for name in RECORD_SETS] if BEYOND else []) + (
    [("risk", name) for name in RECORD_SETS] if BEYOND and config.get("risk") else [])
"""(kind, record set) of the fragility and risk datasets the overview reads."""


# One rule makes every page of `all` (one node of the rule graph instead of one per page).
rule report_pages:
    input:
        claims=f"{OUT}/reproduction/claims.nc",
        comparison=f"{OUT}/reproduction/table1_vs_paper.nc",
        tables=[entry[0] for entry in HTML_TABLES.values()],
        fragility=[f"{OUT}/{kind}/{name}.nc" for kind, name in BEYOND_PAGES_READ if kind == "fragility"],
        risk=[f"{OUT}/{kind}/{name}.nc" for kind, name in BEYOND_PAGES_READ if kind == "risk"],
    output:
        claims=report(f"{OUT}/reproduction/claims.html", caption="../report/claims.rst", category="Reproduction",
                      subcategory="Claims and Table 1",
                      labels=report_pages.labels("Claims of §5 and the Conclusions: PASS / FAIL on this run", "§5, §6")),
        comparison=report(f"{OUT}/reproduction/table1_vs_paper.html", caption="../report/table1_vs_paper.rst",
                          category="Reproduction", subcategory="Claims and Table 1",
                          labels=report_pages.labels("Table 1 of this run beside the paper's, cell by cell", "Table 1")),
        overview=OVERVIEW,
        overview_beyond=OVERVIEW_BEYOND,
        tables=[HTML_PAGES[key] for key in HTML_TABLES],
    log:
        f"{OUT}/logs/report/report_pages.log",
    params:
        expect=expected([f"{OUT}/reproduction/claims.nc", f"{OUT}/reproduction/table1_vs_paper.nc"]
                        + [f"{OUT}/{kind}/{name}.nc" for kind, name in BEYOND_PAGES_READ],
                        [EXPECT.claims(), EXPECT.table1_comparison()]
                        + [getattr(EXPECT, kind)(name) for kind, name in BEYOND_PAGES_READ]),
        pages=REPORT_CODE,
    localrule: True
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/report_pages.py"


REPORT_PAGES = ([entry[0].removesuffix(".md") + ".html" for entry in HTML_TABLES.values()]
                + [f"{OUT}/reproduction/claims.html", f"{OUT}/reproduction/table1_vs_paper.html", OVERVIEW,
                   OVERVIEW_BEYOND])
