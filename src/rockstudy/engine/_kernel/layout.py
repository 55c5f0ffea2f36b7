"""Named layouts of what crosses the boundary of the compiled engine.

Parameters travel as one float vector (numba compiles one signature for it, and a spectrum's
cases are the rows of one matrix); :func:`rockstudy.engine.simulate.pack_parameters` fills it from the
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
I_STRAT = 10     # strategy code (rockstudy.model.control.STRATEGY_CODE)
I_TS = 11        # sampling time T_s, 0 for continuous control [s]
I_DELAY = 12     # actuation delay Δτ [s]
I_VREST = 13     # rest velocity of Eq. (15) [rad/s]
I_RTOL = 14      # relative tolerance [-]
I_ATOL = 15      # absolute tolerance [-]
I_FREE = 16      # free time after the excitation [s]
I_KIND = 17      # ground-motion kind code (rockstudy.model.excitation.KIND_CODE)
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
I_SENSE = 29     # 1: the controller reads Ẍg through a sensor (samples after the record in ``rec``), 0: driving Ẍg
I_SOFF = 30      # index in ``rec`` of the first sensed sample (= number of driving samples) [-]
I_SDT = 31       # sampling step of the sensed samples (1 without sensor) [s]
I_TAYLOR = 32    # 1: Taylor steps between record knots (engine.integrate), 0: Dormand–Prince throughout
NPAR = 33

# ---- the run's constants, fixed by the parameters (engine.setup) ---------------------------
C_KMAX = 0       # κ_max the device applies (0 for FS) [-]
C_KMIN = 1       # κ_min (κ_max for PASSIVE, 0 for FS) [-]
C_CD = 2         # damper coefficient 2ξp (0 for FS) [1/s]
C_EXC_END = 3    # end of the excitation, horizontal or vertical [s]
C_T_STOP = 4     # end of the run: the excitation plus the free time [s]
C_V_END = 5      # end of the vertical record [s]
C_SAMPLED = 6    # 1: sampled control (T_s > 0)
C_SWITCHING = 7  # 1: continuous CS01/CS02 control that switches (κ_max != κ_min)
C_FRACTURE = 8   # 1: elements that can break (not FS, some stiffness or damping)
C_BOUND = 9      # 1: outcome run that may stop below the overturning energy (docs/model.md)
C_BOUND_SWITCHING = 10  # 1: ... with the half-cycle bound of sampled switching control
C_QUIET_KNOTS = 11  # 1: at rest, record knots pass in one tight loop (no sampled control, vertical record, history)
C_TAYLOR = 12    # 1: while the record lasts the steps are Taylor steps (I_TAYLOR, a record, no vertical record)
C_HISTORY = 13   # 1: the run writes its history (rows t, θ, θ̇, κ, Ẍg)
C_LOG = 14       # 1: the run logs its impact, uplift and rest times
C_DRIVEN = 15    # early stop during the excitation: maps.DRIVEN_NONE, DRIVEN_STEADY or DRIVEN_SWITCHING
NCONST = 16

# ---- the early stop's data during the excitation (engine.driven_bound_data), fixed for all amplitudes ----
B_LEVEL = 0      # the level the bound must stay below (maps.cannot_overturn_driven) [-]
B_SCALE = 1      # p/(√2·g): the impulse J per unit of ∫|Ẍg| dt [s/m]
B_PUMP = 2       # p/√2·κ_max·sin θ_a(level): the device's largest pumping of √V₀ per second (switching control) [1/s]
B_UPLIFT = 3     # g·tanα: the |Ẍg| above which a resting block uplifts [m/s^2]
B_RATCHET = 4    # switching device: 12 slots, six pairs (Q̄, c) of the bound without the time left (maps.ratchet_levels)
B_TAIL = 16      # records: from here n slots, ∫ from knot k to the end of the excitation of |record| (upper bound)
                 # [s]; then n slots, the largest |record| from knot k on [-]

# ---- the run's state record: every quantity the driving loop changes (engine.py) ------------
R_T = 0          # time t [s]
R_TH = 1         # θ [rad]
R_THD = 2        # θ̇ [rad/s]
R_SIDE = 3       # pivoting side s (±1) [-]
R_MODE = 4       # MODE_REST, MODE_ROCK or MODE_HOLD
R_KAP_ON = 5     # device state: 1 → κ_max, 0 → κ_min
R_HINT = 6       # sign θ̇ will have right after the current instant (CS01 switch event) [-]
R_H_ON = 7       # 1 while the horizontal excitation lasts
R_T_OVER = 8     # overturning time, NaN until then [s]
R_MAX_ABS = 9    # largest |θ| so far [rad]
R_N_IMPACTS = 10  # impacts so far
R_N_EVENTS = 11  # located events so far (capped by MAX_EVENTS)
R_APEX = 12      # 1: a CS01 apex decision is due before the next step
R_F0_OK = 13     # 1: the derivative R_F0 is still valid at t (FSAL across a known-time event)
R_F0 = 14        # θ̈ at the end of the last accepted step [rad/s^2]
R_H = 15         # next trial step [s]
R_X_HINT = 16    # sign of Ẍg over the current step (CS02 switch event) [-]
R_K_SAMPLE = 17  # index of the next controller sample
R_Q_HEAD = 18    # sampled control: first pending decision in the queue
R_Q_COUNT = 19   # sampled control: pending decisions
R_SPRING = 20    # intact flags of the springs, by corner (LEFT, RIGHT): 2 slots
R_DAMPER = 22    # intact flags of the dampers: 2 slots
R_FRAC = 24      # fracture times: spring L, R, damper L, R (NaN: intact): 4 slots [s]
R_RESUME = 28    # 1: integrate stopped mid-segment for a larger history array; it goes on from here
R_T_NEXT = 29    # ... towards this known-time event [s]
R_N_STEPS = 30   # steps and passes of the driver's loop so far (capped by MAX_STEPS)
R_CHECK = 31     # 1: the early stop's bound during the excitation is tested at the driver's next pass
NSTATE = 32

# ---- fill levels of the growable arrays (engine.drive's ``N``, int64) -------------------------
N_HISTORY = 0    # rows of the history written
N_IMPACTS = 1    # impact times logged
N_UPLIFTS = 2    # uplift times logged
N_RESTS = 3      # rest times logged
NFILL = 4

# ---- how a run ended ---------------------------------------------------------------------
ST_REST, ST_OVER, ST_TLIM, ST_ELIMIT, ST_BOUND = 0, 1, 2, 3, 4
"""At rest after the excitation; overturned; time limit; event cap or step budget (``MAX_EVENTS``,
``MAX_STEPS``); below the overturning energy after the excitation (threshold runs only, see docs/model.md)."""

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
    arrays (a read-only record, e.g. a frozen :class:`~rockstudy.model.noise.NoisyRecord`'s, would make
    numba compile the whole engine a second time)."""
    return a if a.flags.writeable else a.copy()
