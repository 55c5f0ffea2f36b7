"""The engines that integrate the model: :func:`simulate` (one run), its result, the outcome codes,
the compiled event-driven kernel (``_kernel/``) and the scipy reference engine (``reference/``).
"""

