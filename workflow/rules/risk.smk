# Risk at a site (docs/risk.md): per record set of beyond.fragility, the rate and probability of overturning of
# every strategy for the config's scenarios and hazard curves, with the reduction over FS: netCDF, a table and a
# figure. Target: `snakemake -j2 risk` (also in `all`). Needs the optional `risk:` and `beyond:` sections.

RISK = config.get("risk")

if RISK and BEYOND:
    from rockstudy.analysis import risk as risk_analysis

    RISK_HAZARD = risk_analysis.check_config(RISK)  # every scenario in range and hazard file readable, at load
    RISK_FILES = (
        [f"{OUT}/risk/{name}.nc" for name in RECORD_SETS]
        + [f"{OUT}/tables/risk_{name}.{e}" for name in RECORD_SETS for e in ("csv", "md")]
        + [f"{OUT}/figures/risk_{name}.{e}" for name in RECORD_SETS for e in ("png", "pdf")]
    )
    BEYOND_IN_ALL += RISK_FILES  # in place: `all` lists BEYOND_IN_ALL (its HTML pages come with report_pages)

    localrules:
        risk,
        risk_set,
        figure_risk,

    rule risk:
        input:
            RISK_FILES,

    rule risk_set:
        input:
            fragility=f"{OUT}/fragility/{{recordset}}.nc",
            hazard=list((RISK.get("hazard_curves") or {}).values()),
        output:
            nc=f"{OUT}/risk/{{recordset}}.nc",
            csv=f"{OUT}/tables/risk_{{recordset}}.csv",
            md=f"{OUT}/tables/risk_{{recordset}}.md",
        log:
            f"{OUT}/logs/risk/{{recordset}}.log",
        params:
            expect=expect_risk_fragility,
            years=RISK["years"],
            gmm=RISK["gmm"],
            scenarios=RISK.get("scenarios") or {},
            hazard_curves=RISK.get("hazard_curves") or {},
            library=BOOKKEEPING,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/risk.py"

    rule figure_risk:
        input:
            f"{OUT}/risk/{{recordset}}.nc",
        output:
            png=report(f"{OUT}/figures/risk_{{recordset}}.png", caption="../report/risk.rst",
                       category="Figures", subcategory="Records (beyond the paper)",
                       labels=report_pages.labels("Risk of overturning at a site on {recordset}: hazard, fragilities, "
                                                  "disaggregation or scenario probabilities")),
            pdf=f"{OUT}/figures/risk_{{recordset}}.pdf",
        log:
            f"{OUT}/logs/figures/risk_{{recordset}}.log",
        params:
            expect=expect_risk,
            plotting=PLOTTING,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/figure_risk.py"
