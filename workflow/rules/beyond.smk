# Beyond the paper (README "Beyond the paper"): the probability of overturning over the noise
# realisations, and the fragility of each strategy over a suite of (synthetic or recorded)
# earthquakes. Targets: `snakemake -j2 probability`, `snakemake -j2 fragility`. Needs the
# optional `beyond:` section of the config (without it these rules do not exist).

BEYOND = config.get("beyond")
# (checked with the rest of the config by rockstudy.studies.study.check_study)
BEYOND_IN_ALL = []  # the fragility study (about a minute) runs with `all`; the probability surfaces do not

if BEYOND:
    PROB = BEYOND["probability"]
    FRAG = BEYOND["fragility"]
    FRAGILITY_FILES = [f"{OUT}/fragility/fragility.nc", f"{OUT}/tables/fragility.csv", f"{OUT}/tables/fragility.md",
                       f"{OUT}/figures/fragility.png", f"{OUT}/figures/fragility.pdf"]
    BEYOND_IN_ALL = FRAGILITY_FILES
    PROBABILITY_FILES = [f"{OUT}/probability/{s}_{l}.nc" for s in PROB["strategies"] for l in PROB["noise_levels"]]
    if FRAG["records"] == "synthetic":
        RECORD_FILES = [f"{OUT}/records/synthetic/SYN{i:03d}.AT2" for i in range(FRAG["synthetic"]["n_records"])]
        RECORD_UNITS = [None] * len(RECORD_FILES)
    else:
        RECORD_FILES = [entry["path"] for entry in FRAG["records"]]
        RECORD_UNITS = [entry.get("unit") for entry in FRAG["records"]]

    localrules:
        probability,
        fragility,
        figure_probability,
        figure_fragility,

    rule probability:
        input:
            PROBABILITY_FILES,
            expand(f"{OUT}/figures/probability_overturning.{{ext}}", ext=("png", "pdf")),

    rule fragility:
        input:
            FRAGILITY_FILES,
            [f"{OUT}/records/synthetic.nc"] if FRAG["records"] == "synthetic" else [],

    rule probability_surface:
        input:
            noise=f"{OUT}/noise/{{level}}.nc",
        output:
            f"{OUT}/probability/{{strategy}}_{{level}}.nc",
        log:
            f"{OUT}/logs/probability/{{strategy}}_{{level}}.log",
        benchmark:
            f"{OUT}/benchmarks/probability/{{strategy}}_{{level}}.tsv"
        params:
            expect=expect,
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

    if FRAG["records"] == "synthetic":

        rule synthetic_suite:
            output:
                records=RECORD_FILES,
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

    rule fragility_stripes:
        input:
            records=RECORD_FILES,
        output:
            nc=f"{OUT}/fragility/fragility.nc",
            csv=f"{OUT}/tables/fragility.csv",
            md=f"{OUT}/tables/fragility.md",
        log:
            f"{OUT}/logs/fragility/fragility.log",
        benchmark:
            f"{OUT}/benchmarks/fragility/fragility.tsv"
        params:
            scenario=scenario("FS", FREE),
            strategies=FRAG["strategies"],
            units=RECORD_UNITS,
            synthetic=FRAG["synthetic"] if FRAG["records"] == "synthetic" else None,
            intensity_measure=FRAG["intensity_measure"],
            intensity_levels=FRAG["intensity_levels"],
            bootstrap=FRAG["bootstrap"],
            seed=FRAG["seed"],
            library=LIBRARY,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        resources:
            mem_mb=SIM_MEM_MB,
            runtime=15,
        script:
            "../scripts/fragility.py"

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
            expect=expect,
            plotting=PLOTTING,
            a_max0=config["a_max0"],
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/figure_probability.py"

    rule figure_fragility:
        input:
            f"{OUT}/fragility/fragility.nc",
        output:
            png=report(f"{OUT}/figures/fragility.png", caption="../report/fragility.rst", category="Figures",
                       subcategory="Records (beyond the paper)",
                       labels=report_pages.labels("Fragility curves over the record suite; median shift over FS")),
            pdf=f"{OUT}/figures/fragility.pdf",
        log:
            f"{OUT}/logs/figures/fragility.log",
        params:
            expect=expect,
            plotting=PLOTTING,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/figure_fragility.py"
