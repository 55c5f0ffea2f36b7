# Beyond the paper (README "Beyond the paper"): the probability of overturning over the noise
# realisations, and the fragility of each strategy over record suites (FEMA P695 sets, synthetic
# records, files) with every record's threshold. Targets: `snakemake -j2 probability`,
# `snakemake -j2 fragility`. Needs the optional `beyond:` section of the config (without it these
# rules do not exist).

BEYOND = config.get("beyond")
# (checked with the rest of the config by rockstudy.studies.study.check_study)
BEYOND_IN_ALL = []  # the fragility study (about a minute of CPU) runs with `all`; the probability surfaces do not

if BEYOND:
    from rockstudy.studies import beyond as beyond_study

    PROB = BEYOND["probability"]
    FRAG = BEYOND["fragility"]
    RECORD_SETS = beyond_study.record_sets(FRAG["records"])
    FRAGILITY_FILES = (
        [f"{OUT}/fragility/{name}.nc" for name in RECORD_SETS]
        + [f"{OUT}/tables/{t}_{name}.{e}" for t in ("fragility", "record_thresholds") for name in RECORD_SETS
           for e in ("csv", "md")]
        + [f"{OUT}/figures/{f}_{name}.{e}" for f in ("fragility", "record_thresholds") for name in RECORD_SETS
           for e in ("png", "pdf")]
        + [f"{OUT}/tables/fragility_summary.{e}" for e in ("csv", "md")]
    )
    BEYOND_IN_ALL = FRAGILITY_FILES
    PROBABILITY_FILES = [f"{OUT}/probability/{s}_{l}.nc" for s in PROB["strategies"] for l in PROB["noise_levels"]]
    SYNTHETIC_FILES = [f"{OUT}/records/synthetic/SYN{i:03d}.AT2" for i in range(FRAG["synthetic"]["n_records"])]

    wildcard_constraints:
        recordset="|".join(RECORD_SETS),

    localrules:
        probability,
        fragility,
        figure_probability,
        figure_fragility,
        figure_record_thresholds,
        fragility_summary,

    rule probability:
        input:
            PROBABILITY_FILES,
            expand(f"{OUT}/figures/probability_overturning.{{ext}}", ext=("png", "pdf")),

    rule fragility:
        input:
            FRAGILITY_FILES,
            [f"{OUT}/records/synthetic.nc"] + SYNTHETIC_FILES if "synthetic" in RECORD_SETS else [],

    rule probability_surface:
        input:
            noise=f"{OUT}/noise/{{level}}.nc",
            compiled=ancient(COMPILED),
        output:
            f"{OUT}/probability/{{strategy}}_{{level}}.nc",
        log:
            f"{OUT}/logs/probability/{{strategy}}_{{level}}.log",
        params:
            expect=expect_noise,
            scenario=get_scenario,
            realisations=config["realisations"],
            frequency_grid=PROB["frequency_grid"],
            amplitude_grid=PROB["amplitude_grid"],
            library=LIBRARY,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        resources:
            mem_mb=SIM_MEM_MB,
            runtime=30,
        script:
            "../scripts/probability_surface.py"

    if "synthetic" in RECORD_SETS:

        rule synthetic_suite:
            output:
                records=SYNTHETIC_FILES,
                nc=f"{OUT}/records/synthetic.nc",
            log:
                f"{OUT}/logs/records/synthetic.log",
            params:
                synthetic=FRAG["synthetic"],
                library=LIBRARY,
            conda:
                "../envs/rockstudy.yaml"
            threads: 1
            resources:
                mem_mb=SIM_MEM_MB,
                runtime=5,
            script:
                "../scripts/synthetic_suite.py"

    rule record_set:
        input:
            lambda w: beyond_study.set_files(RECORD_SETS[w.recordset]),
        output:
            f"{OUT}/records/sets/{{recordset}}.nc",
        log:
            f"{OUT}/logs/records/{{recordset}}.log",
        params:
            members=lambda w: RECORD_SETS[w.recordset],
            synthetic=FRAG["synthetic"],
            library=LIBRARY,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        resources:
            mem_mb=SIM_MEM_MB,
            runtime=5,
        script:
            "../scripts/record_set.py"

    rule fragility_stripes:
        input:
            records=f"{OUT}/records/sets/{{recordset}}.nc",
            compiled=ancient(COMPILED),
        output:
            nc=f"{OUT}/fragility/{{recordset}}.nc",
            csv=f"{OUT}/tables/fragility_{{recordset}}.csv",
            md=f"{OUT}/tables/fragility_{{recordset}}.md",
            thresholds_csv=f"{OUT}/tables/record_thresholds_{{recordset}}.csv",
            thresholds_md=f"{OUT}/tables/record_thresholds_{{recordset}}.md",
        log:
            f"{OUT}/logs/fragility/{{recordset}}.log",
        params:
            expect=lambda wildcards, input: expected([input.records], [EXPECT.record_set(
                wildcards.recordset, RECORD_SETS[wildcards.recordset])]),
            scenario=scenario("FS", FREE),
            strategies=FRAG["strategies"],
            intensity_measure=FRAG["intensity_measure"],
            intensity_levels=FRAG["intensity_levels"],
            threshold_resolution=FRAG["threshold_resolution"],
            bootstrap=FRAG["bootstrap"],
            seed=FRAG["seed"],
            library=LIBRARY,
            pages=REPORT_CODE,  # the tables it writes
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        resources:
            mem_mb=SIM_MEM_MB,
            runtime=15,
        script:
            "../scripts/fragility.py"

    rule fragility_summary:
        input:
            [f"{OUT}/fragility/{name}.nc" for name in RECORD_SETS],
        output:
            csv=f"{OUT}/tables/fragility_summary.csv",
            md=f"{OUT}/tables/fragility_summary.md",
        log:
            f"{OUT}/logs/fragility/summary.log",
        params:
            expect=expected([f"{OUT}/fragility/{name}.nc" for name in RECORD_SETS],
                            [EXPECT.fragility(name) for name in RECORD_SETS]),
            library=BOOKKEEPING,
            pages=REPORT_CODE,  # the tables it writes
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/fragility_summary.py"

    rule figure_probability:
        input:
            PROBABILITY_FILES,
        output:
            png=report(f"{OUT}/figures/probability_overturning.png", caption="../report/probability.rst",
                       category="Figures", subcategory="Overturning maps",
                       labels=report_pages.labels("P(overturn) over the noise realisations beside the maps")),
            pdf=f"{OUT}/figures/probability_overturning.pdf",
        log:
            f"{OUT}/logs/figures/probability_overturning.log",
        params:
            expect=expected(PROBABILITY_FILES, [EXPECT.probability(s, l) for s in PROB["strategies"]
                                                for l in PROB["noise_levels"]]),
            plotting=PLOTTING,
            a_max0=config["a_max0"],
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/figure_probability.py"

    rule figure_fragility:
        input:
            f"{OUT}/fragility/{{recordset}}.nc",
        output:
            png=report(f"{OUT}/figures/fragility_{{recordset}}.png", caption="../report/fragility.rst",
                       category="Figures", subcategory="Records (beyond the paper)",
                       labels=report_pages.labels("Fragility curves over {recordset}; median shift over FS")),
            pdf=f"{OUT}/figures/fragility_{{recordset}}.pdf",
        log:
            f"{OUT}/logs/figures/fragility_{{recordset}}.log",
        params:
            expect=expect_fragility,
            plotting=PLOTTING,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/figure_fragility.py"

    rule figure_record_thresholds:
        input:
            f"{OUT}/fragility/{{recordset}}.nc",
        output:
            png=report(f"{OUT}/figures/record_thresholds_{{recordset}}.png",
                       caption="../report/record_thresholds.rst", category="Figures",
                       subcategory="Records (beyond the paper)",
                       labels=report_pages.labels("Smallest overturning scale of each record of {recordset}, per strategy")),
            pdf=f"{OUT}/figures/record_thresholds_{{recordset}}.pdf",
        log:
            f"{OUT}/logs/figures/record_thresholds_{{recordset}}.log",
        params:
            expect=expect_fragility,
            plotting=PLOTTING,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/figure_record_thresholds.py"
