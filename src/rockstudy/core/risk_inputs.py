"""Every input of the risk analyses declared once: its range, unit and meaning, and its default.

The library's checks (:mod:`rockstudy.analysis.risk`, :mod:`rockstudy.analysis.ground_motion`), the
command line's (``rockstudy risk``) and the config's ``risk:`` section (:class:`rockstudy.core.declarations.Risk`,
and through it the generated config schema) derive from these declarations.
"""
from __future__ import annotations

from dataclasses import dataclass

from rockstudy.core import validation


@dataclass(frozen=True)
class Bound:
    """Allowed range of one numeric input, its unit and what it is."""

    low: float
    high: float
    unit: str
    description: str
    low_open: bool = True
    high_open: bool = False

    def check(self, name: str, value) -> float:
        """``value`` as a float, or :class:`~rockstudy.core.validation.InputError` naming ``name``.

        Parameters
        ----------
        name : str
            The input's name, as the error message gives it.
        value : float
            The value to check: a finite real number (not a bool) within this bound, in :attr:`unit`.
        """
        return validation.check_range(name, value, self.low, self.high, self.unit, low_open=self.low_open,
                                      high_open=self.high_open)

    def json_schema(self) -> dict:
        """This bound as a JSON Schema of a number."""
        low = "exclusiveMinimum" if self.low_open else "minimum"
        high = "exclusiveMaximum" if self.high_open else "maximum"
        unit = f" [{self.unit}]" if self.unit else ""
        return {"type": "number", low: self.low, high: self.high, "description": self.description + unit}


RISK_INPUTS = {
    "median_g": Bound(0.0, 100.0, "g", "fragility median PGA theta"),
    "dispersion": Bound(0.0, 5.0, "", "fragility dispersion beta (0: a step at the median)", low_open=False),
    "years": Bound(0.0, 10_000.0, "yr", "exposure time T of the probability 1 - exp(-lambda T)"),
    "target_rate": Bound(0.0, 1.0, "1/yr", "target annual rate of overturning"),
    "target_probability": Bound(0.0, 1.0, "", "target probability of overturning in T years", high_open=True),
}
"""Ranges of the fragility, the exposure time and the design targets."""

SCENARIO_INPUTS = {
    "mag": Bound(3.0, 8.5, "", "moment magnitude", low_open=False),
    "dist_rup": Bound(0.0, 300.0, "km", "closest distance to the rupture plane", low_open=False),
    "v_s30": Bound(150.0, 1500.0, "m/s", "time-averaged shear-wave velocity of the top 30 m", low_open=False),
    "dist_jb": Bound(0.0, 300.0, "km", "Joyner-Boore distance (default: dist_rup)", low_open=False),
    "dist_x": Bound(-300.0, 300.0, "km", "site coordinate normal to the strike, R_X (default: dist_jb)",
                    low_open=False),
    "dip": Bound(15.0, 90.0, "deg", "dip of the rupture", low_open=False),
    "depth_tor": Bound(0.0, 20.0, "km", "depth to the top of the rupture", low_open=False),
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

