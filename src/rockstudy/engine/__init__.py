"""The engines that integrate the model: :func:`simulate` (one run), its result, the outcome codes,
the compiled event-driven kernel (``_kernel/``) and the scipy reference engine (``reference/``).
"""

from rockstudy.core.quantities import declare

# the numeric arguments of rockstudy.engine.simulate.simulate (checked there by check_arguments("simulate", ...))
declare("simulate", free_time="free_time", initial_rotation="initial_rotation", initial_velocity="initial_velocity",
        rest_velocity="rest_velocity", rtol="rtol", atol="atol")
