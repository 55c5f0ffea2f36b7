"""Numerical constants of the model and the engines, each defined once with the reason for its value.

Physical parameters (block, anchorage, control timing, excitation) are dataclasses; what lives here
are the fixed choices of the study and of the integrators. ``docs/model.md`` says where each acts.
"""
from __future__ import annotations

FREE_TIME = 30.0
"""Free motion allowed after the excitation before a run stops as "time limit". [s]
Long enough for every block of the study to come to rest (its rocking decays by e per impact)."""

REST_VELOCITY_FACTOR = 1e-6
"""An impact whose rebound |θ̇⁺| is below ``REST_VELOCITY_FACTOR·p·α`` ends the rocking (Eq. 15). [-]
One millionth of the velocity scale p·α: negligible motion, and it ends the infinite impact
sequence of chattering in finite time."""

STANDARD_GRAVITY = 9.80665
"""Standard gravity g_n, the unit "g" of record files. [m/s^2]"""

STANDARD_GRAVITY_UNITS = "9.80665 m s-2"
"""The ``units`` attribute of an acceleration given in units of standard gravity g_n (a PGA "in g"): UDUNITS
and cf-units read ``"g"`` as gram, so netCDF files write g_n itself. The block's model uses its own
``Block.gravity`` (9.81 m/s^2 by default), stated as the ``block_gravity`` attribute where it enters."""

NOISE_DT = 0.0025
"""Sampling step of the noisy records (paper §5). [s]"""

FAST_RTOL = 1e-8
"""Relative tolerance of the fast engine's Dormand–Prince error control. [-]
Thresholds agree with a 1000× tighter tolerance within the scan's resolution (tests/analysis/test_spectra.py)."""

FAST_ATOL = 1e-10
"""Absolute tolerance of the fast engine (θ in rad, θ̇ in rad/s): far below any rotation that matters. [-]"""

REFERENCE_RTOL = 1e-10
"""Relative tolerance of the reference engine (scipy DOP853), 100× tighter than the fast engine. [-]"""

REFERENCE_ATOL = 1e-12
"""Absolute tolerance of the reference engine. [-]"""

MAX_EVENTS = 2_000_000
"""Safety cap on located events per fast-engine run; a run hitting it is "undetermined". [-]
No run of the study comes near it; it turns an unforeseen infinite event loop into a reported outcome."""

MAX_STEPS = 20_000_000
"""Budget of steps per fast-engine run: integration steps and passes of its driving loop together; a
run that spends it is "undetermined", as at the event cap. [-] The study's runs take 10^4 to 10^5;
the budget ends in seconds, in compiled code that Ctrl-C cannot stop, a run whose time scales lie far
below its length (it would step for hours) or whose step or clock stalls."""

NEGLIGIBLE_STEP = 1e-9
"""[s] An excursion from θ = 0 that returns within a step this short is not resolved further: the block
is taken back on the ground at the step's end (θ = θ̇ = 0). Far below every time scale of the model."""

ROTATION_TOLERANCE = 1e-12
"""[rad] A located event within this of a rotation threshold (an ultimate rotation θ_u, the overturning
rotation) counts as reaching it: the event locator stops on either side of the root by round-off."""

IMPACT_TOLERANCE = 1e-14
"""[rad] |θ| below this at a located zero crossing is an impact (θ = 0 up to round-off)."""

TIME_TOLERANCE = 1e-12
"""Relative tolerance for "a step ends at a known-time event" (record knot, controller sample). [-]"""

LOCATE_TOLERANCE = 1e-13
"""Width of the bracket (a fraction of the step) at which the Illinois event locator stops. [-]"""

FIRST_STEP = 1e-3
"""[s] Initial step of the fast engine (error control adapts it at once)."""

MAX_STEP_FRACTION = 0.05
"""Largest step as a fraction of the free-rocking period 2π/p and of the excitation period 2π/ω_p. [-]"""

ENERGY_MARGIN = 1e-6
"""[-] Safety margin of the energy bound that ends a run which can no longer overturn
(docs/engine.md, "Early stops"): the bound must hold by at least this,
far above the integrator's energy drift at FAST_RTOL."""


def rest_velocity(p: float, alpha: float) -> float:
    """Default rest velocity of Eq. (15), ``REST_VELOCITY_FACTOR·p·α``. [rad/s]

    Parameters
    ----------
    p : float
        Frequency parameter of the block. [rad/s]
    alpha : float
        Slenderness angle. [rad]
    """
    return REST_VELOCITY_FACTOR * p * alpha

PAPER = "Use of overturning spectra in the performance evaluation of on-off control strategies for rocking objects"
"""Title of the paper every dataset cites (its ``paper`` attribute)."""

PAPER_VENUE = "conference paper; the copy the study reproduces names neither its authors nor its venue"
"""What is known of where the paper appeared (the text reproduced here has no title page)."""

PAPER_REFERENCE = f"{PAPER}. On-off adaptive control of the anchorages of rigid rocking blocks ({PAPER_VENUE})."
"""Full reference of the paper, the ``references`` attribute of every netCDF file rockstudy writes."""

CF_CONVENTIONS = "CF-1.11"
"""The netCDF conventions every file rockstudy writes follows (its ``Conventions`` attribute)."""
