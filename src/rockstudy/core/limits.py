"""Every limit of the package, written once: input ranges, sizes, loop caps and the names the library accepts.

The declarations (:mod:`rockstudy.core.quantities`), the config's model, the checks of
:mod:`rockstudy.core.validation`, the readers and the engines take their limits from here; a module that
names a limit under its own name (``validation.MAX_TIME_SPAN``) aliases this one. The engines' numerical
constants (tolerances, the fast engine's event and step caps, the noise step) are in
:mod:`rockstudy.core.constants`.

The limits bound everything that becomes an array size, a loop count or a time span. They are derived from
what one machine can do; with the default study a case (one realisation at one frequency) takes about
0.05 s on one core, about 50 simulations of ~1 ms, and needs one noise record of ``duration / 0.0025 s``
samples (8 bytes each).

* :data:`MAX_INTEGER` -- seeds and realisation indices are stored as netCDF ``int64`` attributes and
  coordinates, so they must fit in a signed 64-bit integer.
* :data:`MAX_GRID_POINTS` -- points of one frequency or amplitude grid (a grid of 10^5 points already means
  10^5 cases per realisation; the paper uses about 50).
* :data:`MAX_SIMULATIONS` -- upper bound of the simulations one command or one workflow job may need
  (cases x (coarse grid points + bisection steps)): 10^8 simulations is about one day on one core.
* :data:`MAX_JOBS_PER_SPECTRUM` -- realisation chunks of one spectrum in the workflow (the DAG of all spectra
  must stay small enough for Snakemake to plan).
* :data:`MAX_TIME_SPAN` -- excitation duration plus free time of one simulation. [s]
* :data:`MAX_STEPS` -- integrator steps one simulation may need: its time span over the engine's largest
  step (1/20 of the shorter of the free-rocking and excitation periods).
* :data:`MAX_CONTROLLER_SAMPLES` -- controller samples of one simulation (time span / T_s), half the fast
  engine's event cap of 2 000 000, so sampled control cannot exhaust it.
* :data:`MAX_AMPLITUDE_RATIO`, :data:`MAX_FREQUENCY_RATIO`, :data:`MAX_KAPPA`, :data:`MAX_DAMPING_RATIO` --
  physical ranges far beyond the paper's (amplitude ratios up to 6, frequency ratios up to 5, kappa up to
  1), kept finite so the integrator's step stays resolvable.
* :data:`MIN_RELATIVE_RESOLUTION` -- the bisection of a threshold stops when its bracket is narrower than
  the resolution; below 1e-9 of the scan bound floating point cannot narrow it.
"""
from __future__ import annotations

import math

from rockstudy.core.constants import NOISE_DT

# ------------------------------------------------------------------------------------- work and sizes
MAX_INTEGER = 2**63 - 1
"""Largest seed or realisation index: netCDF ``int64`` attributes hold up to 2^63 - 1."""
MAX_GRID_POINTS = 100_000
"""Largest number of points of one frequency grid or one coarse amplitude grid."""
MAX_REALISATIONS = 100_000
"""Largest number of noise realisations of one spectrum (the paper uses 100)."""
MAX_JOBS_PER_SPECTRUM = 10_000
"""Largest number of realisation chunks (workflow jobs) of one spectrum."""
MAX_SIMULATIONS = 10**8
"""Largest number of simulations one command or workflow job may need (about a day on one core)."""
MAX_STEPS = 10**7
"""Largest number of integrator steps one simulation may need."""
MAX_CONTROLLER_SAMPLES = 10**6
"""Largest number of controller samples (time span / T_s) in one simulation (half the event cap)."""
MAX_RECORD_SAMPLES = MAX_STEPS
"""Largest number of samples of one ground-motion record: the engine ends a step at every sample, so a
record of more samples than :data:`MAX_STEPS` cannot be simulated within that limit."""
MAX_HISTORY_SAMPLES = 2 * MAX_STEPS
"""Largest number of samples of a stored time history (integrator steps or uniform ground samples)."""
MAX_LIST_ITEMS = 200
"""Largest number of entries of one list or mapping of a study config (sampling times, delays, readings,
strategies ...): each entry multiplies the workflow's jobs, and Snakemake plans them all before any runs."""
MAX_BOOTSTRAP = 100_000
"""Largest number of bootstrap draws (the study uses 200)."""
MAX_SUITE_RECORDS = 10_000
"""Largest number of records of one fragility suite (a P695 far-field set has 44)."""
MIN_STRIPES = 2
"""Fewest PGA levels (stripes) of a design fragility: a median and a dispersion need two."""
MAX_DEVICES = 1_000
"""Largest number of devices one calibration screens (every combination of its lists; the study's 48)."""
RECORD_DT = NOISE_DT
"""Sampling step of the noise records (:data:`rockstudy.core.constants.NOISE_DT`). [s]"""
RECORD_BYTES_PER_SAMPLE = 24
"""Bytes held per record sample while a spectrum runs (the record, its baseline and a copy)."""

# ------------------------------------------------------------------------------------- files and text
MAX_RECORD_BYTES = 256 * 2**20
"""Largest record file read (a text record of :data:`MAX_RECORD_SAMPLES` samples takes about 150 MB). [B]"""
MAX_DATASET_BYTES = 2**30
"""Largest netCDF dataset read (a spectrum of the paper's study takes about 100 kB). [B]"""
MAX_DATASET_VALUES = 2 * MAX_STEPS
"""Most values one variable of a netCDF dataset read may declare (a stored history of
:data:`MAX_HISTORY_SAMPLES` samples): the header is read first, so a small file declaring a huge
unwritten variable is refused before anything is loaded."""
MAX_LINE_CHARS = 2**16
"""Longest line of a record file: a record is a few numbers per line (one line of a 255 MB file would be
split into millions of fields, and quoted whole in an error)."""
MAX_TEXT = 4096
"""Longest string of a config (a path or a label)."""
MAX_NODES = 100_000
"""Most nodes (mappings, lists and scalars, aliases expanded) of a config: a few-hundred-byte YAML alias
bomb expands to billions of nodes, so nothing walks a config before this bound is checked."""
SYSTEM_FOLDERS = ("/bin", "/boot", "/etc", "/lib", "/lib32", "/lib64", "/libx32", "/sbin", "/usr", "/var")
"""Folders of the operating system: a results folder may not be one of them or lie inside one (nor be /)."""
PSEUDO_FILESYSTEMS = ("/proc", "/sys", "/dev")
"""Folders no data product may be written to."""
FIGURE_FORMATS = ("png", "pdf", "svg")
"""Suffixes a figure may be written as."""

# ------------------------------------------------------------------------------------- time
MAX_TIME_SPAN = 3600.0
"""Longest simulated time span, excitation plus free time. [s]"""
MAX_FREE_TIME = 3600.0
"""Longest free motion after the excitation. [s]"""
MAX_NOISE_STEP = 0.1
"""Largest sampling step of a noisy record (the study's records use :data:`RECORD_DT`). [s]"""

# ------------------------------------------------------------------------------------- excitation
MAX_AMPLITUDE_RATIO = 1000.0
"""Largest amplitude ratio a_p/(g tan alpha) (for BLC06 about 245 g). [-]"""
MAX_FREQUENCY_RATIO = 1000.0
"""Largest frequency ratio omega_p/p. [-]"""
MIN_RELATIVE_RESOLUTION = 1e-9
"""Smallest amplitude resolution relative to the scan bound (floating point cannot bisect finer)."""
MAX_PGA_G = 100.0
"""Largest peak ground acceleration of a design stripe, a synthetic suite or a fragility median. [g]"""
MIN_PGA_G = 1e-4
"""Smallest peak ground acceleration of a design stripe. [g]"""
MAX_A_MAX0_G = 100.0
"""Largest protection level a_max,0. [g]"""
MAX_RECORD_SCALE = 1e6
"""Largest factor a record is scaled by. [-]"""
MAX_GROUND_ACCELERATION = 2 * MAX_AMPLITUDE_RATIO * 9.80665
"""Largest peak ground acceleration of any ground motion (2000 g): twice the top amplitude ratio for a block of
tan(alpha) = 1, so every scan the declarations allow on a slender block (tan(alpha) <= sqrt(2)) stays below it,
while a strength no declaration allows is refused where the ground motion is made. [m/s^2]"""
MIN_DESIGN_STEP = 1e-3
"""Smallest step of a design block's amplitude scan (it has no stop: it scans up to a_max,0). [-]"""
MIN_DESIGN_RESOLUTION = 1e-6
"""Smallest resolution of a design block's threshold. [-]"""
MAX_GROUND_FREQUENCY_HZ = 1000.0
"""Largest ground frequency of the synthetic suite's Kanai-Tajimi filter (below the Nyquist frequency
of its records too). [Hz]"""
MAX_GROUND_DAMPING = 1.0
"""Largest ground damping ratio of the synthetic suite's Kanai-Tajimi filter. [-]"""
MAX_ENVELOPE_SHAPE = 100.0
"""Largest shape exponent of the synthetic suite's envelope. [-]"""

# ------------------------------------------------------------------------------------- block and devices
MAX_BLOCK_SIZE = 1000.0
"""Largest block dimension. [m]"""
MIN_BLOCK_SIZE = 1e-4
"""Smallest block dimension. [m]"""
MAX_HALF_DIAGONAL = 50.0
"""Largest half diagonal R of a design block. [m]"""
MAX_DENSITY = 1e5
"""Largest block density. [kg/m^3]"""
MAX_GRAVITY = 1000.0
"""Largest acceleration of gravity. [m/s^2]"""
MIN_ALPHA = 1e-3
"""Smallest slenderness alpha of a design block. [rad]"""
MAX_ALPHA = 0.6
"""Largest slenderness alpha of a design block. [rad]"""
MAX_ROTATION = math.pi / 2
"""Largest rotation of a block (a restrainer's ultimate rotation, an initial rotation). [rad]"""
MAX_KAPPA = 1.0e4
"""Largest dimensionless stiffness 4 K b^2/(m g R). [-]"""
MAX_DAMPING_RATIO = 100.0
"""Largest damping ratio xi. [-]"""
MAX_ROTATION_RATIO = 10.0
"""Largest ultimate rotation of a calibration device, as a multiple of alpha. [-]"""
MAX_BAND = 1e6
"""Largest filter cut-off of a noise reading or a sensor. [Hz]"""

# ------------------------------------------------------------------------------------- risk at a site
MAX_DISPERSION = 5.0
"""Largest dispersion beta of a fragility (lognormal standard deviation of ln PGA). [-]"""
MAX_EXPOSURE_YEARS = 10_000.0
"""Longest exposure time of a probability of overturning. [yr]"""
MAX_SCENARIOS = 100
"""Most scenarios (and hazard curves) of a study."""
MAX_HAZARD_SITES = 10_000
"""Most sites a hazard file may hold."""
MAX_HAZARD_POINTS = 100_000
"""Most points a hazard curve may have."""
MAX_HAZARD_BYTES = 16 * 2**20
"""Largest hazard file read. [B]"""
SCENARIO_RANGES = {
    "mag": (3.0, 8.5), "dist_rup": (0.0, 300.0), "v_s30": (150.0, 1500.0), "dist_jb": (0.0, 300.0),
    "dist_x": (-300.0, 300.0), "dip": (15.0, 90.0), "depth_tor": (0.0, 20.0),
}
"""Closed ranges of an earthquake scenario's numbers, the widest the four ground-motion models accept: moment
magnitude, distances [km], V_s30 [m/s], dip [deg] and depth to the top of the rupture [km]."""
GMM_RANGES = {
    "ASK14": {"mag": (3.0, 8.5), "dist_rup": (0.0, 300.0), "v_s30": (180.0, 1000.0), "depth_tor": (0.0, 20.0)},
    "BSSA14": {"mag": (3.0, 8.5), "dist_jb": (0.0, 300.0), "v_s30": (150.0, 1500.0)},
    "CB14": {"mag": (3.3, 8.5), "dist_rup": (0.0, 300.0), "v_s30": (150.0, 1500.0), "depth_tor": (0.0, 20.0)},
    "CY14": {"mag": (3.5, 8.5), "dist_rup": (0.0, 300.0), "v_s30": (180.0, 1500.0), "depth_tor": (0.0, 20.0)},
}
"""Each ground-motion model's published range of applicability (closed intervals): moment magnitude (strike
slip; CB14 and CY14 state lower upper limits for other mechanisms, below), distance [km], V_s30 [m/s] and
depth to the top of the rupture [km], as the NGA-West2 papers give them (Abrahamson et al. 2014, Boore et al.
2014, Campbell & Bozorgnia 2014, Chiou & Youngs 2014; Earthquake Spectra 30(3)); BSSA14's distance is
pygmm's ``LIMITS`` (300 km; the paper allows 400 km)."""
GMM_MAX_MAG_BY_MECHANISM = {"BSSA14": {"SS": 8.5, "RS": 8.5, "NS": 7.0}, "CB14": {"SS": 8.5, "RS": 8.0, "NS": 7.5},
                            "CY14": {"SS": 8.5, "RS": 8.0, "NS": 8.0}}
"""Upper magnitude limits by fault mechanism where a model states them."""
PLAUSIBLE_PGA_HAZARD = {"max_level_g": 10.0, "max_rate_above_1g": 5e-3, "max_rate_above_005g": 1.0}
"""What no PGA hazard curve in g has, used to refuse a file whose unit is not stated and does not look like g:
a level above ``max_level_g`` [g]; an annual rate of exceeding 1 g above ``max_rate_above_1g`` [1/yr] (a
return period of 200 years for 1 g exceeds every published hazard model); an annual rate of exceeding 0.05 g
above ``max_rate_above_005g`` [1/yr]. Stating the unit (g included) reads the file as stated."""

# ------------------------------------------------------------------------------------- integration
RTOL_RANGE = (1e-14, 1e-3)
"""Allowed relative tolerances of the integrators [-]: tighter than 1e-14 is below round-off, looser than 1e-3
is not a result."""
ATOL_RANGE = (1e-16, 1e-3)
"""Allowed absolute tolerances of the integrators (θ in rad, θ̇ in rad/s). [-]"""
REFERENCE_MAX_EVENTS = 5_000_000
"""Cap on the number of pieces of one reference-engine run (guards against an endless event loop)."""
REFERENCE_MAX_STALLED_EVENTS = 10_000
"""Cap on consecutive pieces of a reference-engine run that do not advance time (guards against Zeno loops)."""

# ------------------------------------------------------------------------------------- names
STRATEGIES = ("FS", "PASSIVE", "CS01", "CS02")
"""The control strategies (their order is the compiled engine's code of each)."""
EXCITATIONS = ("modulated", "one-sine")
"""The paper's pulse excitations."""
OVERTURN_CRITERIA = ("flat", "alpha")
"""When a run counts as overturned: lying flat (|θ| >= π/2) or once past the uplift-free limit (|θ| >= α)."""
RESCALES = ("energy", "pga", "both", "none")
"""How the sum baseline + noise is rescaled (``NoiseReading.rescale``)."""
LEVEL_MEANINGS = ("energy", "rms")
"""What the noise level r measures (``NoiseReading.level_means``)."""
