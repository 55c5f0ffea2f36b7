# Reproducing the paper's numbers (issue 9): the readings study of the loose noise model, the device
# calibration, and the claims checklist of §5 and the Conclusions.
REPRO = config["reproduction"]
READINGS = REPRO["readings"]
READING_SPECTRA = [f"{OUT}/reproduction/readings/spectra/{REPRO['strategy']}_{name}_{level}.nc"
                   for name in READINGS for level in NOISY]


wildcard_constraints:
    reading="[A-Za-z0-9_]+",


def reading_scenario(wildcards):
    spec = scenario(wildcards.strategy, wildcards.level)
    spec["noise"] = dict(READINGS[wildcards.reading])  # missing keys: the library defaults
    return spec


rule reading_spectrum:
    output:
        f"{OUT}/reproduction/readings/spectra/{{strategy}}_{{reading}}_{{level}}.nc",
    log:
        f"{OUT}/logs/reproduction/readings/{{strategy}}_{{reading}}_{{level}}.log",
    benchmark:
        f"{OUT}/benchmarks/reproduction/readings/{{strategy}}_{{reading}}_{{level}}.tsv"
    params:
        scenario=reading_scenario,
        reading_name=lambda w: w.reading,
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
