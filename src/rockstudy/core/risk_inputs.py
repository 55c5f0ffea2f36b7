"""Every input of the risk analyses declared once: its range, unit and meaning, and its default.

The library's checks (:mod:`rockstudy.analysis.risk`, :mod:`rockstudy.analysis.ground_motion`), the
command line's (``rockstudy risk``) and the config's ``risk:`` section (:class:`rockstudy.core.declarations.Risk`,
and through it the generated config schema) derive from these declarations.
"""
from __future__ import annotations

from rockstudy.core.quantities import Quantity

RISK_INPUTS = {
    "median_g": Quantity(0.0, 100.0, "g", "fragility median PGA theta"),
    "dispersion": Quantity(0.0, 5.0, "", "fragility dispersion beta (0: a step at the median)", low_open=False),
    "years": Quantity(0.0, 10_000.0, "yr", "exposure time T of the probability 1 - exp(-lambda T)"),
    "target_rate": Quantity(0.0, 1.0, "1/yr", "target annual rate of overturning"),
    "target_probability": Quantity(0.0, 1.0, "", "target probability of overturning in T years", high_open=True),
}
"""Ranges of the fragility, the exposure time and the design targets."""

SCENARIO_INPUTS = {
    "mag": Quantity(3.0, 8.5, "", "moment magnitude", low_open=False),
    "dist_rup": Quantity(0.0, 300.0, "km", "closest distance to the rupture plane", low_open=False),
    "v_s30": Quantity(150.0, 1500.0, "m/s", "time-averaged shear-wave velocity of the top 30 m", low_open=False),
    "dist_jb": Quantity(0.0, 300.0, "km", "Joyner-Boore distance (default: dist_rup)", low_open=False),
    "dist_x": Quantity(-300.0, 300.0, "km", "site coordinate normal to the strike, R_X (default: dist_jb)",
                    low_open=False),
    "dip": Quantity(15.0, 90.0, "deg", "dip of the rupture", low_open=False),
    "depth_tor": Quantity(0.0, 20.0, "km", "depth to the top of the rupture", low_open=False),
}
"""Ranges of a scenario's numbers: the widest the four ground-motion models accept."""
SCENARIO_REQUIRED = ("mag", "dist_rup", "v_s30")
"""What every scenario gives."""
MECHANISMS = ("SS", "NS", "RS")
"""Fault mechanisms: strike slip, normal, reverse."""
SCENARIO_DEFAULTS = {"mechanism": "SS", "dip": 90.0, "depth_tor": 0.0}
"""Fault mechanism, dip [deg] and depth to the top of the rupture [km] unless given: a vertical strike-slip
rupture reaching the surface (``dist_jb`` and ``dist_x`` then default to ``dist_rup``, the site off the
rupture's end)."""

GMMS = {"ASK14": "AbrahamsonSilvaKamai2014", "BSSA14": "BooreStewartSeyhanAtkinson2014",
        "CB14": "CampbellBozorgnia2014", "CY14": "ChiouYoungs2014"}
"""The ground-motion models offered (NGA-West2), by their usual abbreviation, with pygmm's class names."""
DEFAULT_GMM = "ASK14"
"""The ground-motion model used unless another is named."""
DEFAULT_YEARS = 50.0
"""Exposure time of the probabilities. [yr]"""
MAX_SCENARIOS = 100
"""Most scenarios (and hazard curves) of a study."""


# --- hazard files ----------------------------------------------------------------------------------
HAZARD_UNITS = {"g": 1.0, "m/s2": 1 / 9.80665, "cm/s2": 1 / 980.665, "%g": 0.01}
"""Units a hazard file's PGA levels may be stated in, with the value of one unit in g (standard gravity
g_n = 9.80665 m/s²). OpenQuake, nshmp-haz and the USGS hazard tool write PGA in g."""
HAZARD_UNIT_ALIASES = {"m/s^2": "m/s2", "m s-2": "m/s2", "cm/s^2": "cm/s2", "gal": "cm/s2", "percent_g": "%g"}
"""Other spellings of :data:`HAZARD_UNITS` accepted on input."""
PLAUSIBLE_PGA_HAZARD = {"max_level_g": 10.0, "max_rate_above_1g": 5e-3, "max_rate_above_005g": 1.0}
"""What no PGA hazard curve in g has, used to refuse a file whose unit is not stated and does not look like g:
a level above ``max_level_g`` [g]; an annual rate of exceeding 1 g above ``max_rate_above_1g`` [1/yr] (a
return period of 200 years for 1 g exceeds every published hazard model); an annual rate of exceeding 0.05 g
above ``max_rate_above_005g`` [1/yr]. Stating the unit (g included) reads the file as stated."""
MAX_HAZARD_SITES = 10_000
"""Most sites a hazard file may hold."""

# --- ground-motion models' published ranges -----------------------------------------------------------
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
