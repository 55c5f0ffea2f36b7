# The pictures and numbers the README and docs/ quote, made from this run's own files:
# `snakemake -j2 docs` (not in `all`) copies them into docs/figures/, where tests/test_docs_numbers.py
# compares every fragility median the docs quote with docs/figures/run_numbers.csv.

DOCS_FIGURES = ["fig3_history_CS02.png", "fig4_excitation.png", "fig6_noise_sensitivity.png", "maps_overturning.png"]
if BEYOND:
    DOCS_FIGURES += ["record_thresholds_p695-far-field.png"] if "p695-far-field" in RECORD_SETS else []
    DOCS_FIGURES += ["risk_p695-far-field.png"] if "p695-far-field" in RECORD_SETS and config.get("risk") else []
"""Figures of the run shown in the README and docs (docs/figures/<name>; docs/gallery.md shows them all)."""


rule docs:
    input:
        figures=[f"{OUT}/figures/{name}" for name in DOCS_FIGURES],
        fragility=[f"{OUT}/fragility/{name}.nc" for name in RECORD_SETS] if BEYOND else [],
    output:
        figures=[f"docs/figures/{name}" for name in DOCS_FIGURES],
        numbers="docs/figures/run_numbers.csv",
    log:
        f"{OUT}/logs/docs.log",
    params:
        expect=expected([f"{OUT}/fragility/{name}.nc" for name in RECORD_SETS] if BEYOND else [],
                        [EXPECT.fragility(name) for name in RECORD_SETS] if BEYOND else []),
        pages=REPORT_CODE,  # the numbers it writes
    localrule: True
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/docs_files.py"
