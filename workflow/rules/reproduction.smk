# Reproducing the paper's numbers: the readings study of the loose noise model, the device
# calibration, and the claims checklist of §5 and the Conclusions.


rule reading_spectrum:
    input:
        compiled=ancient(COMPILED),
    output:
        f"{OUT}/reproduction/readings/spectra/{{strategy}}_{{reading}}_{{level}}.nc",
    log:
        f"{OUT}/logs/reproduction/readings/{{strategy}}_{{reading}}_{{level}}.log",
    params:
        scenario=get_reading_scenario,
        realisations=REPRO["realisations"],
        frequency_grid=config["frequency_grid"],
        amplitude_grid=config["amplitude_grid"],
        library=LIBRARY,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    resources:
        mem_mb=SIM_MEM_MB,
        runtime=CHUNK_RUNTIME * max(1, -(-REPRO["realisations"] // config["realisations_per_job"])),
    script:
        "../scripts/reading_spectrum.py"


rule reading_spectra:
    input:
        READING_SPECTRA,


rule claims:
    input:
        table1=f"{OUT}/tables/table1.nc",
        sampling=f"{OUT}/tables/timing_sampling.nc",
        delay=f"{OUT}/tables/timing_delay.nc",
        convergence=CONVERGENCE_FILE,
        spectra=spectrum_files(FIG6_PANELS, LEVELS),
    output:
        md=f"{OUT}/reproduction/claims.md",
        nc=f"{OUT}/reproduction/claims.nc",
        csv=f"{OUT}/reproduction/claims.csv",
        comparison_nc=f"{OUT}/reproduction/table1_vs_paper.nc",
        comparison_csv=f"{OUT}/reproduction/table1_vs_paper.csv",
    log:
        f"{OUT}/logs/reproduction/claims.log",
    params:
        expect=report_pages.ExpectedAttributes({**expected([f"{OUT}/tables/{t}.nc" for t in ("table1", "timing_sampling", "timing_delay")],
                           [EXPECT.table1(), EXPECT.timing_table("sampling"), EXPECT.timing_table("delay")]),
                **CONVERGENCE, **expected(spectrum_files(FIG6_PANELS, LEVELS), spectra_expected(FIG6_PANELS, LEVELS))}),
        bookkeeping=BOOKKEEPING,
        pages=REPORT_CODE,  # the checklist it writes
        noise_levels=LEVELS,
        a_max0=config["a_max0"],
        reading=config["noise"],
        anchorage=config["anchorage"],
        realisations=config["realisations"],
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/claims.py"


rule readings_table:
    input:
        spectra=READING_SPECTRA,
        reference=f"{OUT}/spectra/{REPRO['strategy']}_{FREE}.nc",
    output:
        nc=f"{OUT}/reproduction/readings/readings.nc",
        csv=f"{OUT}/reproduction/readings/readings.csv",
        md=f"{OUT}/reproduction/readings/readings.md",
    log:
        f"{OUT}/logs/reproduction/readings_table.log",
    params:
        expect=report_pages.ExpectedAttributes({**expected(READING_SPECTRA, READING_SPECTRA_EXPECTED),
                **expected([f"{OUT}/spectra/{REPRO['strategy']}_{FREE}.nc"], [EXPECT.spectrum(REPRO["strategy"], FREE)])}),
        bookkeeping=BOOKKEEPING,
        spectrum_keys=[(name, level) for name in READINGS for level in NOISY],
        readings=READINGS,
        levels={level: LEVELS[level] for level in NOISY},
        a_max0=config["a_max0"],
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/readings_table.py"


rule figure_readings:
    input:
        f"{OUT}/reproduction/readings/readings.nc",
    output:
        png=report(f"{OUT}/reproduction/readings/fig_readings.png", caption="../report/readings_figure.rst",
                   category="Reproduction", subcategory="Noise readings",
                   labels=report_pages.labels("FS row of Table 1 under each reading of the noise model (figure)",
                                              "§5, Table 1")),
        pdf=f"{OUT}/reproduction/readings/fig_readings.pdf",
    log:
        f"{OUT}/logs/reproduction/figure_readings.log",
    params:
        expect=expected([f"{OUT}/reproduction/readings/readings.nc"], [EXPECT.readings_table()]),
        plotting=PLOTTING,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/figure_readings.py"


rule reproduction:
    input:
        READINGS_TABLE,
        READINGS_FIGURE,
        f"{OUT}/reproduction/readings/readings.html",  # the table as a page of the report


# --- the device calibration (a separate target: snakemake -j2 calibration) ------------------------

rule calibration_fs:
    input:
        compiled=ancient(COMPILED),
    output:
        CAL_FS,
    log:
        f"{OUT}/logs/reproduction/calibration/fs.log",
    params:
        scenarios=[scenario("FS", level) for level in LEVELS],
        realisations=CAL["coarse_realisations"],
        frequency_grid=CAL["coarse_frequency_grid"],
        amplitude_grid=config["amplitude_grid"],
        library=LIBRARY,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    resources:
        mem_mb=SIM_MEM_MB,
        runtime=30,
    script:
        "../scripts/calibration_fs.py"


rule calibration_device:
    input:
        fs=CAL_FS,
        compiled=ancient(COMPILED),
    output:
        f"{OUT}/reproduction/calibration/coarse/device{{device}}.nc",
    log:
        f"{OUT}/logs/reproduction/calibration/device{{device}}.log",
    wildcard_constraints:
        device="[0-9]+",
    params:
        expect=expected(CAL_FS, [EXPECT.calibration_fs(level) for level in LEVELS]),
        scenario=calibration_base(),
        anchorage=get_device_anchorage,
        levels=LEVELS,
        realisations=CAL["coarse_realisations"],
        frequency_grid=CAL["coarse_frequency_grid"],
        amplitude_grid=config["amplitude_grid"],
        a_max0=config["a_max0"],
        library=LIBRARY,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    resources:
        mem_mb=SIM_MEM_MB,
        runtime=60,
    script:
        "../scripts/calibration_device.py"


rule calibration_grid:
    input:
        CAL_DEVICE_FILES,
    output:
        nc=f"{OUT}/reproduction/calibration/grid.nc",
        png=report(f"{OUT}/reproduction/calibration/fig_calibration.png", caption="../report/calibration.rst",
                   category="Reproduction", subcategory="Device calibration",
                   labels=report_pages.labels("J_OS over the screened anchorages (figure)", "Table 1")),
        pdf=f"{OUT}/reproduction/calibration/fig_calibration.pdf",
    log:
        f"{OUT}/logs/reproduction/calibration/grid.log",
    params:
        expect=expected(CAL_DEVICE_FILES, [EXPECT.calibration_device(i) for i in range(len(CAL_DEVICES))]),
        design=CAL_DESIGN,
        alpha=CAL_ALPHA,
        reading=config["noise"],
        bookkeeping=BOOKKEEPING,
        plotting=PLOTTING,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/calibration_grid.py"


rule calibration_refine_spectrum:
    input:
        grid=f"{OUT}/reproduction/calibration/grid.nc",
        compiled=ancient(COMPILED),
    output:
        f"{OUT}/reproduction/calibration/refine/c{{rank}}_{{strategy}}_{{level}}.nc",
    log:
        f"{OUT}/logs/reproduction/calibration/refine_c{{rank}}_{{strategy}}_{{level}}.log",
    wildcard_constraints:
        rank="[0-9]+",
    params:
        expect=expected([f"{OUT}/reproduction/calibration/grid.nc"], [EXPECT.calibration_grid()]),
        scenario=calibration_base(),
        noise_level=get_noise_level,
        realisations=config["realisations"],
        frequency_grid=config["frequency_grid"],
        amplitude_grid=config["amplitude_grid"],
        library=LIBRARY,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    resources:
        mem_mb=SIM_MEM_MB,
        runtime=CHUNK_RUNTIME * max(1, -(-config["realisations"] // config["realisations_per_job"])),
    script:
        "../scripts/calibration_refine_spectrum.py"


rule calibration_refine:
    input:
        grid=f"{OUT}/reproduction/calibration/grid.nc",
        fs=fs_spectra_of_the_study(),
        spectra=CAL_REFINE,
    output:
        nc=f"{OUT}/reproduction/calibration/candidates.nc",
        md=f"{OUT}/reproduction/calibration/calibration.md",
    log:
        f"{OUT}/logs/reproduction/calibration/refine.log",
    params:
        expect=report_pages.ExpectedAttributes({**expected([f"{OUT}/reproduction/calibration/grid.nc"] + CAL_REFINE,
                           [EXPECT.calibration_grid()] + [EXPECT.calibration_refined(*key) for key in CAL_REFINE_KEYS]),
                **expected(fs_spectra_of_the_study(), spectra_expected(["FS"], LEVELS))}),
        block=config["block"],
        candidates=CAL["candidates"],
        levels=LEVELS,
        a_max0=config["a_max0"],
        reading=config["noise"],
        bookkeeping=BOOKKEEPING,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/calibration_refine.py"


rule calibration:
    input:
        f"{OUT}/reproduction/calibration/calibration.html",  # the table as a page of the report
        f"{OUT}/reproduction/calibration/grid.nc",
        f"{OUT}/reproduction/calibration/candidates.nc",
        f"{OUT}/reproduction/calibration/calibration.md",
