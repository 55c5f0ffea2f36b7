# Risk at a site (docs/risk.md): per record set of beyond.fragility, the rate and probability of overturning of
# every strategy for the config's scenarios and hazard curves, with the reduction over FS: netCDF, a table and a
# figure; with hazard files of several sites, a map of the probability per strategy. Target: `snakemake -j2 risk`
# (also in `all`). Needs the optional `risk:` and `beyond:` sections.

RISK = config.get("risk")

if RISK and BEYOND:
    from rockstudy.studies import risk as risk_section

    RISK_HAZARD = risk_section.check_config(RISK)  # every scenario in range and hazard file readable, at load
    RISK_MAPPED_SITES = sum(s.lon is not None and s.lat is not None for sites in RISK_HAZARD.values() for s in sites)
    RISK_FILES = (
        [f"{OUT}/risk/{name}.nc" for name in RECORD_SETS]
        + [f"{OUT}/tables/risk_{name}.{e}" for name in RECORD_SETS for e in ("csv", "md")]
        + [f"{OUT}/figures/risk_{name}.{e}" for name in RECORD_SETS for e in ("png", "pdf")]
        + ([f"{OUT}/figures/risk_sites_{name}.{e}" for name in RECORD_SETS for e in ("png", "pdf")]
           if RISK_MAPPED_SITES > 1 else [])
    )
    BEYOND_IN_ALL += RISK_FILES  # in place: `all` lists BEYOND_IN_ALL (its HTML pages come with report_pages)

    localrules:
        risk,
        risk_set,
        figure_risk,
        figure_risk_sites,

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
            hazard_units=RISK.get("hazard_units") or {},
            outside_gmm_range=bool(RISK.get("outside_gmm_range")),
            library=BOOKKEEPING,
            pages=REPORT_CODE,  # the tables it writes
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

    rule figure_risk_sites:
        input:
            f"{OUT}/risk/{{recordset}}.nc",
        output:
            png=report(f"{OUT}/figures/risk_sites_{{recordset}}.png", caption="../report/risk_sites.rst",
                       category="Figures", subcategory="Records (beyond the paper)",
                       labels=report_pages.labels("Risk of overturning at every site of the hazard files: a map "
                                                  "per strategy")),
            pdf=f"{OUT}/figures/risk_sites_{{recordset}}.pdf",
        log:
            f"{OUT}/logs/figures/risk_sites_{{recordset}}.log",
        params:
            expect=expect_risk,
            plotting=PLOTTING,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/figure_risk_sites.py"
