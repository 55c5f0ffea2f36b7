"""Every input of the risk analyses declared once: its range, unit and meaning, and its default.

The library's checks (:mod:`rockstudy.analysis.risk`, :mod:`rockstudy.analysis.ground_motion`), the
command line's (``rockstudy risk``) and the config's ``risk:`` section (:class:`rockstudy.studies.config_model.Risk`,
and through it the generated config schema) derive from these declarations.
"""
from __future__ import annotations

from rockstudy.core.limits import (  # noqa: F401 -- the risk limits, read here by the analyses
    GMM_MAX_MAG_BY_MECHANISM,
    GMM_RANGES,
    MAX_DISPERSION,
    MAX_EXPOSURE_YEARS,
    MAX_HAZARD_BYTES,
    MAX_HAZARD_POINTS,
    MAX_HAZARD_SITES,
    MAX_PGA_G,
    MAX_SCENARIOS,
    PLAUSIBLE_PGA_HAZARD,
    SCENARIO_RANGES,
)
from rockstudy.core.quantities import Quantity

RISK_INPUTS = {
    "median_g": Quantity(0.0, MAX_PGA_G, "g", "fragility median PGA theta"),
    "dispersion": Quantity(0.0, MAX_DISPERSION, "", "fragility dispersion beta (0: a step at the median)",
                           low_open=False),
    "years": Quantity(0.0, MAX_EXPOSURE_YEARS, "yr", "exposure time T of the probability 1 - exp(-lambda T)"),
    "target_rate": Quantity(0.0, 1.0, "1/yr", "target annual rate of overturning"),
    "target_probability": Quantity(0.0, 1.0, "", "target probability of overturning in T years", high_open=True),
}
"""Ranges of the fragility, the exposure time and the design targets."""

SCENARIO_INPUTS = {
    "mag": Quantity(*SCENARIO_RANGES["mag"], "", "moment magnitude", low_open=False),
    "dist_rup": Quantity(*SCENARIO_RANGES["dist_rup"], "km", "closest distance to the rupture plane", low_open=False),
    "v_s30": Quantity(*SCENARIO_RANGES["v_s30"], "m/s", "time-averaged shear-wave velocity of the top 30 m",
                      low_open=False),
    "dist_jb": Quantity(*SCENARIO_RANGES["dist_jb"], "km", "Joyner-Boore distance (default: dist_rup)", low_open=False),
    "dist_x": Quantity(*SCENARIO_RANGES["dist_x"], "km", "site coordinate normal to the strike, R_X (default: dist_jb)",
                    low_open=False),
    "dip": Quantity(*SCENARIO_RANGES["dip"], "deg", "dip of the rupture", low_open=False),
    "depth_tor": Quantity(*SCENARIO_RANGES["depth_tor"], "km", "depth to the top of the rupture", low_open=False),
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


# --- hazard files ----------------------------------------------------------------------------------
HAZARD_UNITS = {"g": 1.0, "m/s2": 1 / 9.80665, "cm/s2": 1 / 980.665, "%g": 0.01}
"""Units a hazard file's PGA levels may be stated in, with the value of one unit in g (standard gravity
g_n = 9.80665 m/s²). OpenQuake, nshmp-haz and the USGS hazard tool write PGA in g."""
HAZARD_UNIT_ALIASES = {"m/s^2": "m/s2", "m s-2": "m/s2", "cm/s^2": "cm/s2", "gal": "cm/s2", "percent_g": "%g"}
"""Other spellings of :data:`HAZARD_UNITS` accepted on input."""
