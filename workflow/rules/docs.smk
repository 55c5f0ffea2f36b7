# The pictures and numbers the README and docs/ quote, made from this run's own files:
# `snakemake -j2 docs` (not in `all`) copies them into docs/figures/, where tests/test_docs_numbers.py
# compares every fragility median the docs quote with docs/figures/run_numbers.csv.

DOCS_FIGURES = ["fig6_noise_sensitivity.png"]
"""Figures of the run shown in the README and docs (docs/figures/<name>)."""


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
    localrule: True
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/docs_files.py"
