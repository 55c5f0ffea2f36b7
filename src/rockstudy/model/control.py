"""On-off control of the anchorage stiffness (paper §3, Eqs. 16–17, and §5.2 timing).

Strategies
----------
FS       free standing, no anchorage at all (K = D = 0);
PASSIVE  anchorage with constant K = K_max;
CS01     feedback: K_max while theta·theta_dot >= 0, K_min otherwise (Eq. 16);
CS02     feedback-feedforward: while the ground acceleration is non-zero, K_max when
         Xg_ddot·theta <= 0 and K_min otherwise; CS01 once it is zero (Eq. 17).

Sign convention (Makris): a positive horizontal ground acceleration drives theta
negative, so "the ground pushes the block outward" means Xg_ddot·theta < 0 and CS02
then holds the block with K_max.

Timing: with sampling_time T_s > 0 the controller reads theta, theta_dot and Xg_ddot
at t_k = k·T_s and its decision takes effect at t_k + delay (zero-order hold).
T_s = 0 is continuous control (then delay must be 0).

Sensing: with sensor_band = None the controller reads the Xg_ddot that drives the block;
with a band f_c [Hz] it reads it through a causal second-order Butterworth low-pass
(an accelerometer and controller filter, rockstudy.model.sensor); the block still feels the
driving Xg_ddot.
"""
from __future__ import annotations

from dataclasses import InitVar, dataclass

from rockstudy.core._inline import njit
from rockstudy.core.limits import STRATEGIES
from rockstudy.core.quantities import check_arguments, declares
from rockstudy.core.validation import field_names

STRATEGY_CODE = {name: i for i, name in enumerate(STRATEGIES)}
"""Integer code of each strategy, the one the compiled engine reads."""
FS, PASSIVE, CS01, CS02 = (STRATEGY_CODE[name] for name in STRATEGIES)


@declares(sampling_time="sampling_time", delay="delay", sensor_band="band")
@dataclass(frozen=True)
class Control:
    """Control strategy and its timing.

    Parameters
    ----------
    strategy : {"FS", "PASSIVE", "CS01", "CS02"}
        Control law.
    sampling_time : float, default 0
        Controller sampling time T_s; 0 means continuous control. [s]
    delay : float, default 0
        Actuation delay between a sample and the moment its decision acts. [s]
    sensor_band : float or None, default None
        Cut-off f_c of the sensor through which the controller reads Ẍg (a causal second-order
        Butterworth low-pass of the record, :mod:`rockstudy.model.sensor`); None: the controller reads
        the driving Ẍg itself (the ideal sensor). Only CS02 reads Ẍg. [Hz]
    names : dict, optional
        The caller's name of each field in error messages (``{"delay": "--delay"}``); a field missing from it
        is named ``Control.<field>``. Not stored.

    Raises
    ------
    ValueError
        (:class:`~rockstudy.core.validation.InputError` for a range) naming the field, its value and what is
        allowed: the one check of a control, at construction (:meth:`check`).
    """

    strategy: str = "CS01"
    sampling_time: float = 0.0
    delay: float = 0.0
    sensor_band: float | None = None
    names: InitVar[dict | None] = None

    def __post_init__(self, names):
        band = self.check(names, **self.__dict__)
        object.__setattr__(self, "sensor_band", band)

    @staticmethod
    def check(names=None, *, strategy="CS01", sampling_time=0.0, delay=0.0, sensor_band=None) -> float | None:
        """Refuse a bad field with a ``ValueError`` naming it ``names[field]`` (the caller's option or config
        key), else ``Control.<field>``; returns the sensor band as a float (or None).

        Parameters
        ----------
        names : dict or None, default None
            Name of each field in the error message, e.g. ``{"sampling_time": "--sampling-time"}``; a field
            missing from it is named ``Control.<field>``.
        strategy : {"FS", "PASSIVE", "CS01", "CS02"}
            Control law.
        sampling_time, delay : float
            Controller sampling time and actuation delay, finite, >= 0; a delay > 0 needs a sampling time > 0. [s]
        sensor_band : float or None
            Sensor cut-off, > 0, or None for the ideal sensor. [Hz]
        """
        name = field_names("Control", names)
        if strategy not in STRATEGIES:
            raise ValueError(f"{name('strategy')} must be one of {', '.join(STRATEGIES)}, got {strategy!r}")
        checked = check_arguments("Control", {"sampling_time": sampling_time, "delay": delay,
                                              "sensor_band": sensor_band}, names)
        if sampling_time == 0 and delay > 0:
            raise ValueError(
                f"{name('delay')} > 0 needs a {name('sampling_time')} > 0: a delay acts on sampled decisions "
                f"(got {name('sampling_time')}=0, {name('delay')}={delay})"
            )
        # None: the ideal sensor; the Nyquist limit depends on the record (rockstudy.model.sensor.check_band)
        return checked["sensor_band"]

    @property
    def code(self) -> int:
        return STRATEGY_CODE[self.strategy]

    def to_attrs(self) -> dict:
        return {"control_strategy": self.strategy, "control_sampling_time_s": self.sampling_time,
                "control_delay_s": self.delay,
                "control_sensor_band_hz": "none" if self.sensor_band is None else self.sensor_band}


@njit(cache=True)
def cs01_is_on(theta, theta_dot):
    """Eq. (16): True (K = K_max) when θ·θ̇ >= 0, the block moving away from upright.

    Parameters
    ----------
    theta : float
        Rotation θ (or its sign). [rad]
    theta_dot : float
        Angular velocity θ̇ (or its sign). [rad/s]
    """
    return theta * theta_dot >= 0.0


@njit(cache=True)
def cs02_is_on(theta, theta_dot, ground_acceleration):
    """Eq. (17) in the Makris sign convention: True (K = K_max) when the ground pushes outward.

    With Ẍg != 0: K_max when Ẍg·θ <= 0; with Ẍg == 0: CS01 (Eq. 16).

    Parameters
    ----------
    theta : float
        Rotation θ (or its sign). [rad]
    theta_dot : float
        Angular velocity θ̇ (or its sign). [rad/s]
    ground_acceleration : float
        Ẍg (or its sign). [m/s^2]
    """
    if ground_acceleration != 0.0:
        return ground_acceleration * theta <= 0.0
    return cs01_is_on(theta, theta_dot)


@njit(cache=True)
def stiffness_on(strategy, theta, theta_dot, ground_acceleration):
    """Output of the control law of ``strategy`` (a ``STRATEGY_CODE``): True for K_max.

    CS01: Eq. (16); CS02: Eq. (17); FS and PASSIVE: always True (their stiffness does not switch).
    Both engines decide with this function.
    """
    if strategy == CS02:
        return cs02_is_on(theta, theta_dot, ground_acceleration)
    if strategy == CS01:
        return cs01_is_on(theta, theta_dot)
    return True
