"""The physical model: the block, its anchorage and control laws, the equation of motion, and the
ground motions that drive it (the paper's excitations, noise, sensors and earthquake records).

Nothing here integrates anything: these modules define parameters (frozen dataclasses), the
paper's formulas as compiled scalar functions, and how excitations are built. The engines in
:mod:`rockstudy.engine` integrate them.
"""

