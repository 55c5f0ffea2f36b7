# Names, paths and parameter dictionaries shared by the rules.
import re

from rockstudy.studies import expectations, fingerprints

OUT = config["results_dir"]
LEVELS = config["noise_levels"]
FREE = parameters.noise_free_level(LEVELS)
NOISY = [name for name in LEVELS if name != FREE]
# Source fingerprints by layer (rockstudy's subpackages): a job reruns when the code it runs changes.
LIBRARY = fingerprints.source_fingerprint()  # the simulation layers: core, model, engine, analysis
BOOKKEEPING = fingerprints.source_fingerprint("core", "analysis", "studies")  # what assembles datasets and tables
PLOTTING = fingerprints.source_fingerprint("plotting")  # redraw the figures when the plotting package changes
# The report shows what a fingerprint covers, not its hash (the hash still decides the rerun).
LIBRARY = report_pages.SourceFingerprint(LIBRARY, "core, model, engine, analysis")
BOOKKEEPING = report_pages.SourceFingerprint(BOOKKEEPING, "core, analysis, studies")
PLOTTING = report_pages.SourceFingerprint(PLOTTING, "plotting")
REPORT_CODE = report_pages.SourceFingerprint(fingerprints.source_fingerprint("report"), "report")  # the HTML pages
COMPILED_SCAN = f"{OUT}/logs/compile_engine.done"  # the threshold scans compiled into numba's cache (compile_engine)
COMPILED_PARTS = f"{OUT}/logs/compile_engine_parts.done"  # their parts besides the step loop, compiled beside it
COMPILED = f"{OUT}/logs/compile_engine_more.done"  # and everything else the simulation jobs call (compile_engine_more)
SAMPLING = config["sampling_sweep"]
DELAY = config["delay_sweep"]
EX = config["example_point"]
HIST = config["control_histories"]
PAPER_FIGURE = {"CS01": "2", "CS02": "3", "FS": "0", "PASSIVE": "0"}  # 0: not in the paper


wildcard_constraints:
    strategy="FS|PASSIVE|CS01|CS02",
    level="[A-Za-z0-9]+",
    ts="[0-9.e-]+",
    delay="[0-9.e-]+",
    chunk="[0-9]+",
    reading="[A-Za-z0-9_]+",


def scenario(strategy, level, ts=0.0, delay=0.0):
    return expectations.scenario_spec(config, strategy, level, ts, delay)


# What every dataset a step reads must say about itself (params `expect` of a rule: {file: attributes}),
# derived from the job's wildcards and the config by rockstudy.studies.expectations. The step's reader
# (rockstudy.studies.jobs) compares each input with it and with the dataset's own invariants: a stale,
# swapped or edited file stops the step, naming the file, instead of becoming a right-looking result.
EXPECT = expectations.StudyExpectations(config)


def expected(paths, expectations_in_order):
    """Parameter ``expect`` of a rule: {file: expectation} of its input files and their expectations, in order
    (shown in the report as one line, see rockstudy.report.ExpectedAttributes)."""
    return report_pages.ExpectedAttributes(expectations.paired(paths, expectations_in_order))


# Resources measured with the default config on one core (the last line of each job's log): a spectrum chunk
# takes about 0.05 s per (realisation x frequency) at 5 % noise and peaks at 250 MB, like
# every simulation job (numba + xarray); maps take seconds. Requests carry a margin of 2-3x.
SIM_MEM_MB = 600


CHUNK_RUNTIME = 5 + int(0.15 * config["realisations_per_job"] * len(parameters.frequency_ratios(config["frequency_grid"]))
                      / 60.0 + 1)
"""Minutes to request for one spectrum chunk: 5 + 0.15 s per (realisation x frequency)."""


def chunks(level):
    return EXPECT.chunks(level)


# A spectrum whose realisations fit in one job (realisations_per_job >= realisations, and always the
# noise-free level) is written whole by that job (rule spectrum); the others are simulated in chunks and
# gathered (rules spectrum_chunk, gather_*). Which rules exist is decided here, from the config.
WHOLE_LEVELS = [level for level in LEVELS if len(chunks(level)) == 1]
CHUNKED_LEVELS = [level for level in LEVELS if level not in WHOLE_LEVELS]


def scan_priority(n_noisy_spectra):
    """Snakemake priority of a job that computes ``n_noisy_spectra`` noisy spectra one after the other: the
    longest jobs start first, so that the last ones running do not leave a core idle while the others wait
    (longest first); below the compile's 100."""
    return 1 + n_noisy_spectra


def one_of(names):
    """A wildcard constraint matching exactly these names."""
    return "|".join(re.escape(name) for name in names)


# Input and parameter functions of the rules (Snakemake calls them with the job's wildcards).
def get_scenario(wildcards):
    """The scenario of a job: its strategy, and its noise level (default: noise-free), sampling time and delay."""
    return scenario(wildcards.strategy, getattr(wildcards, "level", FREE), getattr(wildcards, "ts", 0.0),
                    getattr(wildcards, "delay", 0.0))


def get_level_scenarios(wildcards):
    """The scenarios of a strategy's spectra at the noise levels of one job each (rule spectrum)."""
    return [scenario(wildcards.strategy, level) for level in WHOLE_LEVELS]


def get_level_realisations(wildcards):
    """Every realisation of each of those levels, in the same order: each level's one chunk."""
    return [list(chunks(level)[0]) for level in WHOLE_LEVELS]


def get_sampling_scenarios(wildcards):
    """The scenarios of a strategy's sampling sweep, one per configured sampling time (rule spectrum_sampling)."""
    return [scenario(wildcards.strategy, wildcards.level, ts) for ts in SAMPLING["sampling_times"]]


def get_delay_scenarios(wildcards):
    """The scenarios of a strategy's delay sweep at the job's sampling time, one per configured delay."""
    return [scenario(wildcards.strategy, wildcards.level, wildcards.ts, d) for d in DELAY["delays"]]


def get_noise_scenario(wildcards):
    """The scenario whose noise records a level's noise file holds (the records do not depend on the strategy)."""
    return scenario("FS", wildcards.level)


def get_realisations(wildcards):
    """Every realisation of the job's noise level (one, 0, without noise)."""
    return [k for chunk in chunks(wildcards.level) for k in chunk]


def get_chunk_realisations(wildcards):
    """The realisations of the job's chunk."""
    return chunks(wildcards.level)[int(wildcards.chunk)]


def get_noise_level(wildcards):
    """The job's noise level: noise energy / baseline energy. [-]"""
    return LEVELS[wildcards.level]


def get_realisation(wildcards):
    return int(wildcards.k)


def get_frequency_ratio(wildcards):
    return float(wildcards.frequency)


def get_amplitude_ratio(wildcards):
    return float(wildcards.amplitude)


def get_control_history_file(wildcards):
    """The noise-free history of Figs. 2-3 for the job's strategy."""
    return history_file(wildcards.strategy, FREE, 0, HIST["frequency_ratio"], HIST["amplitude_ratio"])


def chunk_files(wildcards, ts="0", delay="0"):
    path = f"{OUT}/spectra/chunks/{{strategy}}_{{level}}_Ts{{ts}}_d{{delay}}_c{{chunk}}.nc"
    ts, delay = getattr(wildcards, "ts", ts), getattr(wildcards, "delay", delay)
    return [path.format(strategy=wildcards.strategy, level=wildcards.level, ts=ts, delay=delay, chunk=c)
            for c in range(len(chunks(wildcards.level)))]


def spectrum_files(strategies, levels):
    return [f"{OUT}/spectra/{s}_{l}.nc" for s in strategies for l in levels]


def history_file(strategy, level, k, frequency_ratio, amplitude_ratio):
    return f"{OUT}/histories/{strategy}_{level}_k{k}_w{frequency_ratio:g}_a{amplitude_ratio:g}.nc"


def spectra_expected(strategies, levels):
    """The expectations of spectrum_files(strategies, levels), in its order."""
    return [EXPECT.spectrum(s, l) for s in strategies for l in levels]


def sampling_file(strategy, level, ts):
    return f"{OUT}/timing/sampling/{strategy}_{level}_Ts{ts:g}.nc"


# the timing sweeps' spectra: (strategy, level, sampling time[, delay]) of each file
SAMPLING_KEYS = [(s, SAMPLING["noise_level"], ts) for s in SAMPLING["strategies"] for ts in SAMPLING["sampling_times"]]
DELAY_KEYS = [(s, DELAY["noise_level"], DELAY["sampling_time"], d) for s in DELAY["strategies"] for d in DELAY["delays"]]
DELAY_REFERENCE_KEYS = [(s, DELAY["noise_level"], DELAY["sampling_time"]) for s in DELAY["strategies"]]
SAMPLING_FILES = [sampling_file(*key) for key in SAMPLING_KEYS]
DELAY_FILES = [f"{OUT}/timing/delay/{s}_{l}_Ts{ts:g}_d{d:g}.nc" for s, l, ts, d in DELAY_KEYS]
DELAY_REFERENCES = [sampling_file(*key) for key in DELAY_REFERENCE_KEYS]  # sampled, without delay
EX_HISTORIES = [history_file(EX["strategy"], EX["noise_level"], k, EX["frequency_ratio"], EX["amplitude_ratio"])
                for k in EX["realisations"]]
EX_HISTORIES_EXPECTED = [EXPECT.history(EX["strategy"], EX["noise_level"], k, EX["frequency_ratio"],
                                        EX["amplitude_ratio"]) for k in EX["realisations"]]
FIG = f"{OUT}/figures/{{name}}.{{ext}}"
FIGURE_NAMES = ([f"fig{PAPER_FIGURE[s]}_history_{s}" for s in HIST["strategies"]]
                + ["fig4_excitation", "fig5_realisations", "fig6_noise_sensitivity", "fig7_sampling",
                   "fig8_delay", "maps_overturning"])
FIGURES = [FIG.format(name=n, ext=e) for n in FIGURE_NAMES for e in ("png", "pdf")]
TABLES = [f"{OUT}/tables/{t}.{e}" for t in ("table1", "timing_sampling", "timing_delay") for e in ("nc", "csv", "md")]


# params `expect` of the rules whose inputs depend on the job's wildcards
def expect_noise(wildcards, input):
    """The job's noise file: its level's realisations (rules spectrum*, probability_surface)."""
    return expected([input.noise], [EXPECT.noise(wildcards.level)])


def expect_noise_levels(wildcards, input):
    """The noise file of each level of a strategy's spectra job, in order (rule spectrum)."""
    return expected(list(input.noise), [EXPECT.noise(level) for level in WHOLE_LEVELS])


def expect_chunks(wildcards, input):
    """The chunks of the spectrum a gather job writes, in order (rules gather_*)."""
    ts, delay = getattr(wildcards, "ts", 0.0), getattr(wildcards, "delay", 0.0)
    return expected(input, [EXPECT.chunk(wildcards.strategy, wildcards.level, ts, delay, c)
                            for c in range(len(chunks(wildcards.level)))])


def expect_spectrum(wildcards, input):
    """The job's whole spectrum (rule convergence)."""
    return expected(input, [EXPECT.spectrum(wildcards.strategy, wildcards.level)])


def expect_control_history(wildcards, input):
    """The noise-free history of Figs. 2-3 (rule figure_history)."""
    return expected(input, [EXPECT.history(wildcards.strategy, FREE, 0, HIST["frequency_ratio"],
                                           HIST["amplitude_ratio"])])


def expect_fragility(wildcards, input):
    """The fragility of the job's record set (rules figure_fragility, figure_record_thresholds)."""
    return expected(input, [EXPECT.fragility(wildcards.recordset)])


def expect_risk_fragility(wildcards, input):
    """The fragility of the job's record set (rule risk_set; its hazard files are text)."""
    return expected([input.fragility], [EXPECT.fragility(wildcards.recordset)])


def expect_risk(wildcards, input):
    """The risk dataset of the job's record set (rule figure_risk)."""
    return expected(input, [EXPECT.risk(wildcards.recordset)])


# Reproducing the paper's numbers: readings study, claims checklist, device calibration.
REPRO = config["reproduction"]
READINGS = REPRO["readings"]
STUDY_READING = parameters.reading_from_dict(config["noise"])
SAME_AS_STUDY = [name for name in READINGS if parameters.reading_from_dict(READINGS[name]) == STUDY_READING
                 and REPRO["realisations"] == config["realisations"] and REPRO["strategy"] in config["strategies"]]
"""Readings equal to the study's own ``noise:`` reading, with its realisations: the readings study reuses the
study's gathered spectra for them (same block, seed, grids and realisations, so the same records)."""


def reading_spectrum_file(name, level):
    """The spectrum of reading ``name`` at ``level``: the study's own when the reading is the study's."""
    if name in SAME_AS_STUDY:
        return spectrum_files([REPRO["strategy"]], [level])[0]
    return f"{OUT}/reproduction/readings/spectra/{REPRO['strategy']}_{name}_{level}.nc"


def fs_spectra_of_the_study():
    """FS spectra of the study's reading at every level (the calibration's references at full settings)."""
    return spectrum_files(["FS"], LEVELS)


def reading_spectrum_expected(name, level):
    """What reading_spectrum_file(name, level) must say about itself."""
    if name in SAME_AS_STUDY:
        return EXPECT.spectrum(REPRO["strategy"], level)
    return EXPECT.reading_spectrum(REPRO["strategy"], name, level)


READING_SPECTRA = [reading_spectrum_file(name, level) for name in READINGS for level in NOISY]
READING_SPECTRA_EXPECTED = [reading_spectrum_expected(name, level) for name in READINGS for level in NOISY]


def get_reading_scenario(wildcards):
    return expectations.reading_scenario_spec(config, wildcards.strategy, wildcards.reading, wildcards.level)


READINGS_TABLE = [f"{OUT}/reproduction/readings/readings.{e}" for e in ("nc", "csv", "md")]
READINGS_FIGURE = [f"{OUT}/reproduction/readings/fig_readings.{e}" for e in ("png", "pdf")]
CLAIMS = [f"{OUT}/reproduction/{name}" for name in ("claims.md", "claims.nc", "claims.csv", "table1_vs_paper.nc",
                                                     "table1_vs_paper.csv")]
CAL = config["calibration"]
CAL_DESIGN = {key: CAL[key] for key in ("kappa_max", "damping_ratio", "ultimate_rotation_ratio", "kappa_min_ratio")}
CAL_ALPHA = parameters.block_from_dict(config["block"]).alpha  # theta_u = ratio * alpha
CAL_DEVICES = EXPECT.calibration_devices
CAL_FS = [f"{OUT}/reproduction/calibration/coarse/FS_{level}.nc" for level in LEVELS]
CAL_DEVICE_FILES = [f"{OUT}/reproduction/calibration/coarse/device{i}.nc" for i in range(len(CAL_DEVICES))]
CAL_REFINE_KEYS = [(rank, s, level) for rank in range(CAL["candidates"]) for s in ("CS01", "CS02") for level in LEVELS]
CAL_REFINE = [f"{OUT}/reproduction/calibration/refine/c{rank}_{s}_{level}.nc" for rank, s, level in CAL_REFINE_KEYS]


def calibration_base():
    spec = scenario("FS", FREE)
    base = {k: v for k, v in spec.items() if k not in ("anchorage", "control", "noise_level")}
    return {**base, "control_options": dict(config["control"])}  # the sensor, for every strategy


def get_device_anchorage(wildcards):
    """The anchorage of the job's calibration device."""
    return CAL_DEVICES[int(wildcards.device)]
