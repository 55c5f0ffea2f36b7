"""Named layouts of what crosses the boundary of the compiled engine.

Parameters travel as one float vector (numba compiles one signature for it, and a spectrum's
cases are the rows of one matrix); :func:`rockstudy.simulate.pack_parameters` fills it from the
dataclasses and every slot has a name here. Results come back as the :class:`KernelResult`
named tuple.
"""
from __future__ import annotations

from collections import namedtuple

# ---- parameter vector: one named slot per parameter ------------------------------------
I_P = 0          # frequency parameter p [rad/s]
I_ALPHA = 1      # slenderness α [rad]
I_G = 2          # gravity g [m/s^2]
I_E = 3          # restitution e, Eq. (14) [-]
I_KMAX = 4       # κ_max [-]
I_KMIN = 5       # κ_min [-]
I_CD = 6         # damper coefficient 2ξp [1/s]
I_TKU = 7        # spring ultimate rotation θ_K,u [rad]
I_TDU = 8        # damper ultimate rotation θ_D,u [rad]
I_TOVER = 9      # overturning rotation (π/2 or α) [rad]
I_STRAT = 10     # strategy code (rockstudy.control.STRATEGY_CODE)
I_TS = 11        # sampling time T_s, 0 for continuous control [s]
I_DELAY = 12     # actuation delay Δτ [s]
I_VREST = 13     # rest velocity of Eq. (15) [rad/s]
I_RTOL = 14      # relative tolerance [-]
I_ATOL = 15      # absolute tolerance [-]
I_FREE = 16      # free time after the excitation [s]
I_KIND = 17      # ground-motion kind code (rockstudy.excitation.KIND_CODE)
I_AMP = 18       # amplitude a_p (factor of the record for records) [m/s^2]
I_OMEGA = 19     # ω_p (1 when the kind has none) [rad/s]
I_DUR = 20       # duration of the horizontal excitation [s]
I_RDT = 21       # record sampling step (1 without record) [s]
I_VDT = 22       # vertical record sampling step (1 without one) [s]
I_TH0 = 23       # initial θ [rad]
I_THD0 = 24      # initial θ̇ [rad/s]
I_HMAX = 25      # largest step [s]
I_SINA = 26      # sin α [-]
I_COSA = 27      # cos α [-]
I_BOUND = 28     # 1: end runs that provably cannot overturn any more (energy bound), 0: integrate on
NPAR = 29

# ---- how a run ended ---------------------------------------------------------------------
ST_REST, ST_OVER, ST_TLIM, ST_ELIMIT, ST_BOUND = 0, 1, 2, 3, 4
"""At rest after the excitation; overturned; time limit; event cap; below the overturning energy
after the excitation (threshold runs only, see docs/model.md)."""

# ---- the engine's modes --------------------------------------------------------------------
MODE_REST, MODE_ROCK, MODE_HOLD = 0, 1, 2
"""On the ground (θ = θ̇ = 0); rocking (integrated); held on the CS01 sliding surface (θ̇ = 0)."""

LEFT, RIGHT = 0, 1
"""Index of the corner elements: left works for θ > 0 (Eq. 13), right for θ < 0 (Eq. 12)."""

KernelResult = namedtuple("KernelResult", [
    "status",            # ST_* code
    "overturn_time",     # [s], NaN if not overturned
    "end_time",          # [s]
    "max_abs_theta",     # [rad]
    "n_impacts",
    "impact_times",      # [s] (logged runs only)
    "uplift_times",      # [s]
    "rest_times",        # [s]
    "fracture_times",    # [s] spring L, spring R, damper L, damper R; NaN if intact
    "history",           # n × 5: t, θ, θ̇, κ, Ẍg (on request)
])


def writable(a):
    """``a`` itself when writable, else a copy: the compiled entry points are typed for writable
    arrays (a read-only record, e.g. a frozen :class:`~rockstudy.noise.NoisyRecord`'s, would make
    numba compile the whole engine a second time)."""
    return a if a.flags.writeable else a.copy()
