# Simulations: noise realisations, overturning spectra (whole, or in realisation chunks gathered), maps,
# histories.


# The engine compiled into numba's cache in three parts: the threshold scans (the spectra wait for them
# alone) and, beside them, what the step loop, the driver and the scan call, which the scans then load;
# then the rest of what the simulation jobs call, beside the first spectra.
COMPILE_PARAMS = dict(scenario=scenario("CS01", (NOISY or [FREE])[0]), library=LIBRARY)
"""What every compile job runs on (its part is its own): the first noisy level's CS01 scenario."""


rule compile_engine:
    output:
        COMPILED_SCAN,
    priority: 100  # first: every spectrum waits for it, while the jobs that need no compiled code do not
    log:
        f"{OUT}/logs/compile_engine.log",
    params:
        **COMPILE_PARAMS,
        part="scan",
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    resources:
        mem_mb=SIM_MEM_MB,
        runtime=10,
    script:
        "../scripts/compile_engine.py"


use rule compile_engine as compile_engine_parts with:
    output:
        COMPILED_PARTS,
    log:
        f"{OUT}/logs/compile_engine_parts.log",
    params:
        **COMPILE_PARAMS,
        part="parts",


use rule compile_engine as compile_engine_more with:
    input:
        ancient(COMPILED_SCAN),
        ancient(COMPILED_PARTS),
    output:
        COMPILED,
    log:
        f"{OUT}/logs/compile_engine_more.log",
    params:
        **COMPILE_PARAMS,
        part="more",


rule noise:
    output:
        f"{OUT}/noise/{{level}}.nc",
    log:
        f"{OUT}/logs/noise/{{level}}.log",
    group:
        "small"
    params:
        bookkeeping=BOOKKEEPING,
        scenario=get_noise_scenario,
        frequency_grid=config["frequency_grid"],
        realisations=get_realisations,
        reference_frequency_ratio=config["noise_reference_frequency_ratio"],
        n_records=config["noise_records_stored"],
        library=LIBRARY,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    resources:
        mem_mb=SIM_MEM_MB,
        runtime=5,
    script:
        "../scripts/noise.py"


# What every job that scans the study's grids is given besides its own params (the spectra, whole, swept
# or in chunks, and the maps): the grids and the source fingerprint. A rule derived by `use rule ... with:
# params:` states its params in full, since that replaces the whole block.
SCAN_PARAMS = dict(
    frequency_grid=config["frequency_grid"],
    amplitude_grid=config["amplitude_grid"],
    library=LIBRARY,
)


ONE_LEVEL_INPUT = dict(noise=f"{OUT}/noise/{{level}}.nc", compiled=ancient(COMPILED_SCAN))
"""The inputs of a job that simulates at one noise level (the timing sweeps, the chunks)."""


# A strategy's spectra at every noise level whose realisations fit one job (WHOLE_LEVELS: always the
# noise-free one), one job per strategy writing them one after the other in one process: each job's
# start-up (about 1 s of imports and compiled-code loading) is paid once per strategy, not once per
# spectrum. Each spectrum is written whole, as gathering its one chunk would write it.
rule spectrum:
    input:
        noise=[f"{OUT}/noise/{level}.nc" for level in WHOLE_LEVELS],
        compiled=ancient(COMPILED_SCAN),
    output:
        [f"{OUT}/spectra/{{strategy}}_{level}.nc" for level in WHOLE_LEVELS],
    log:
        f"{OUT}/logs/spectra/{{strategy}}.log",
    priority: scan_priority(len([level for level in WHOLE_LEVELS if level != FREE]))
    group:
        "spectra"
    params:
        expect=expect_noise_levels,
        scenario=get_level_scenarios,
        realisations=get_level_realisations,
        whole=True,
        **SCAN_PARAMS,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    resources:
        mem_mb=SIM_MEM_MB,
        runtime=CHUNK_RUNTIME * len(WHOLE_LEVELS),
    script:
        "../scripts/spectrum.py"


# The timing sweeps (Figs. 7-8): one job writes a strategy's whole sweep, a spectrum per sampling time
# (per delay), one after the other in one process, as the rule above does over the noise levels.
use rule spectrum as spectrum_sampling with:
    input:
        **ONE_LEVEL_INPUT,
    wildcard_constraints:
        level=one_of(WHOLE_LEVELS),
    output:
        [f"{OUT}/timing/sampling/{{strategy}}_{{level}}_Ts{ts:g}.nc" for ts in SAMPLING["sampling_times"]],
    log:
        f"{OUT}/logs/timing/sampling/{{strategy}}_{{level}}.log",
    priority: scan_priority(len(SAMPLING["sampling_times"]))
    params:
        expect=expect_noise,
        scenario=get_sampling_scenarios,
        realisations=get_realisations,
        whole=True,
        **SCAN_PARAMS,
    resources:
        mem_mb=SIM_MEM_MB,
        runtime=CHUNK_RUNTIME * len(SAMPLING["sampling_times"]),


use rule spectrum as spectrum_delay with:
    input:
        **ONE_LEVEL_INPUT,
    wildcard_constraints:
        level=one_of(WHOLE_LEVELS),
    output:
        [f"{OUT}/timing/delay/{{strategy}}_{{level}}_Ts{{ts}}_d{d:g}.nc" for d in DELAY["delays"]],
    log:
        f"{OUT}/logs/timing/delay/{{strategy}}_{{level}}_Ts{{ts}}.log",
    priority: scan_priority(len(DELAY["delays"]))
    params:
        expect=expect_noise,
        scenario=get_delay_scenarios,
        realisations=get_realisations,
        whole=True,
        **SCAN_PARAMS,
    resources:
        mem_mb=SIM_MEM_MB,
        runtime=CHUNK_RUNTIME * len(DELAY["delays"]),


if CHUNKED_LEVELS:

    localrules:
        gather_spectrum,
        gather_sampling,
        gather_delay,

    use rule spectrum as spectrum_chunk with:
        input:
            **ONE_LEVEL_INPUT,
        output:
            f"{OUT}/spectra/chunks/{{strategy}}_{{level}}_Ts{{ts}}_d{{delay}}_c{{chunk}}.nc",
        log:
            f"{OUT}/logs/spectra/chunks/{{strategy}}_{{level}}_Ts{{ts}}_d{{delay}}_c{{chunk}}.log",
        wildcard_constraints:
            level=one_of(CHUNKED_LEVELS),
        params:
            expect=expect_noise,
            scenario=get_scenario,
            realisations=get_chunk_realisations,
            whole=False,
            **SCAN_PARAMS,

    rule gather_spectrum:
        input:
            chunk_files,
        output:
            f"{OUT}/spectra/{{strategy}}_{{level}}.nc",
        log:
            f"{OUT}/logs/spectra/{{strategy}}_{{level}}.log",
        wildcard_constraints:
            level=one_of(CHUNKED_LEVELS),
        params:
            expect=expect_chunks,
            bookkeeping=BOOKKEEPING,
            realisations=get_realisations,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/gather_spectra.py"

    use rule gather_spectrum as gather_sampling with:
        output:
            f"{OUT}/timing/sampling/{{strategy}}_{{level}}_Ts{{ts}}.nc",
        log:
            f"{OUT}/logs/timing/sampling/{{strategy}}_{{level}}_Ts{{ts}}.log",

    use rule gather_spectrum as gather_delay with:
        output:
            f"{OUT}/timing/delay/{{strategy}}_{{level}}_Ts{{ts}}_d{{delay}}.nc",
        log:
            f"{OUT}/logs/timing/delay/{{strategy}}_{{level}}_Ts{{ts}}_d{{delay}}.log",


rule convergence:
    input:
        f"{OUT}/spectra/{{strategy}}_{{level}}.nc",
    output:
        f"{OUT}/convergence/{{strategy}}_{{level}}.nc",
    log:
        f"{OUT}/logs/convergence/{{strategy}}_{{level}}.log",
    params:
        expect=expect_spectrum,
        bookkeeping=BOOKKEEPING,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/convergence.py"


rule overturning_map:
    input:
        compiled=ancient(COMPILED),
    output:
        f"{OUT}/maps/{{strategy}}.nc",
    log:
        f"{OUT}/logs/maps/{{strategy}}.log",
    params:
        scenario=get_scenario,
        **SCAN_PARAMS,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    resources:
        mem_mb=SIM_MEM_MB,
        runtime=15,
    script:
        "../scripts/overturning_map.py"


rule time_history:
    input:
        compiled=ancient(COMPILED),
    output:
        f"{OUT}/histories/{{strategy}}_{{level}}_k{{k}}_w{{frequency}}_a{{amplitude}}.nc",
    log:
        f"{OUT}/logs/histories/{{strategy}}_{{level}}_k{{k}}_w{{frequency}}_a{{amplitude}}.log",
    group:
        "small"
    params:
        bookkeeping=BOOKKEEPING,
        scenario=get_scenario,
        realisation=get_realisation,
        frequency_ratio=get_frequency_ratio,
        amplitude_ratio=get_amplitude_ratio,
        library=LIBRARY,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    resources:
        mem_mb=SIM_MEM_MB,
        runtime=5,
    script:
        "../scripts/time_history.py"


rule table1:
    input:
        spectrum_files(config["table1"]["strategies"], LEVELS),
    output:
        nc=f"{OUT}/tables/table1.nc",
        csv=f"{OUT}/tables/table1.csv",
        md=f"{OUT}/tables/table1.md",
    log:
        f"{OUT}/logs/tables/table1.log",
    params:
        expect=expected(spectrum_files(config["table1"]["strategies"], LEVELS),
                        spectra_expected(config["table1"]["strategies"], LEVELS)),
        bookkeeping=BOOKKEEPING,
        strategies=config["table1"]["strategies"],
        noise_levels=LEVELS,
        a_max0=config["a_max0"],
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/table1.py"


rule timing_table_sampling:
    input:
        sweep=SAMPLING_FILES,
        same_strategy=spectrum_files(SAMPLING["strategies"], [SAMPLING["noise_level"]]),
        free_standing=spectrum_files(["FS"], [SAMPLING["noise_level"]]),
    output:
        nc=f"{OUT}/tables/timing_sampling.nc",
        csv=f"{OUT}/tables/timing_sampling.csv",
        md=f"{OUT}/tables/timing_sampling.md",
    log:
        f"{OUT}/logs/tables/timing_sampling.log",
    params:
        expect=report_pages.ExpectedAttributes({
            **expected(SAMPLING_FILES, [EXPECT.spectrum(*key) for key in SAMPLING_KEYS]),
            **expected(spectrum_files(SAMPLING["strategies"], [SAMPLING["noise_level"]]),
                       spectra_expected(SAMPLING["strategies"], [SAMPLING["noise_level"]])),
            **expected(spectrum_files(["FS"], [SAMPLING["noise_level"]]),
                       spectra_expected(["FS"], [SAMPLING["noise_level"]])),
        }),
        bookkeeping=BOOKKEEPING,
        variable="sampling_time",
        reference="continuous_same_noise",
        a_max0=config["a_max0"],
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/timing_table.py"


rule timing_table_delay:
    input:
        sweep=DELAY_FILES,
        same_strategy=DELAY_REFERENCES,
        free_standing=spectrum_files(["FS"], [DELAY["noise_level"]]),
    output:
        nc=f"{OUT}/tables/timing_delay.nc",
        csv=f"{OUT}/tables/timing_delay.csv",
        md=f"{OUT}/tables/timing_delay.md",
    log:
        f"{OUT}/logs/tables/timing_delay.log",
    params:
        expect=report_pages.ExpectedAttributes({
            **expected(DELAY_FILES, [EXPECT.spectrum(*key) for key in DELAY_KEYS]),
            **expected(DELAY_REFERENCES, [EXPECT.spectrum(*key) for key in DELAY_REFERENCE_KEYS]),
            **expected(spectrum_files(["FS"], [DELAY["noise_level"]]), spectra_expected(["FS"], [DELAY["noise_level"]])),
        }),
        bookkeeping=BOOKKEEPING,
        variable="delay",
        reference="sampled_without_delay_same_noise",
        a_max0=config["a_max0"],
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/timing_table.py"
