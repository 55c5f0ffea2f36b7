"""The physical model: the block, its anchorage and control laws, the equation of motion, and the
ground motions that drive it (the paper's excitations, noise, sensors and earthquake records).

Nothing here integrates anything: these modules define parameters (frozen dataclasses), the
paper's formulas as compiled scalar functions, and how excitations are built. The engines in
:mod:`rockstudy.engine` integrate them.
"""

from rockstudy.core.quantities import declare

# the numeric arguments of rockstudy.model.noise's NoiseReading, noise_generator and noisy_record (checked there
# by check_arguments)
declare("NoiseReading", step="noise_step", band="band", span="noise_span")
declare("noise_generator", seed="seed", level="noise_level", realisation="realisation")
declare("noisy_record", omega="circular_frequency", level="noise_level", realisation="realisation", seed="seed")
