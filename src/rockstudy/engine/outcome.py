"""Outcome of one run at one amplitude: the codes shared by the engine, the threshold scan and the
datasets (the ``outcome`` variable's ``flag_values``/``flag_meanings``)."""
from __future__ import annotations

from enum import IntEnum


class Outcome(IntEnum):
    """What one simulation at one amplitude ratio showed.

    NO_UPLIFT
        The record cannot lift the block (its peak is below g·tanα): not simulated.
    SAFE
        At rest, at the time limit, or proved unable to overturn any more.
    OVERTURNED_WITHOUT_IMPACT
        Overturned on its first excursion.
    OVERTURNED_AFTER_IMPACT
        Overturned after at least one impact (θ = 0).
    UNDETERMINED
        The fast engine hit its event cap or step budget (``constants.MAX_EVENTS``, ``MAX_STEPS``); counted
        as not overturned.
    """

    NO_UPLIFT = 0
    SAFE = 1
    OVERTURNED_WITHOUT_IMPACT = 2
    OVERTURNED_AFTER_IMPACT = 3
    UNDETERMINED = 4

    @property
    def meaning(self) -> str:
        """The CF ``flag_meanings`` word of this outcome."""
        return self.name.lower()

    @property
    def overturned(self) -> bool:
        return self in (Outcome.OVERTURNED_WITHOUT_IMPACT, Outcome.OVERTURNED_AFTER_IMPACT)


OUTCOME_MEANINGS = tuple(o.meaning for o in Outcome)
"""``flag_meanings`` of the datasets, in code order."""

# plain ints for the compiled engine (numba reads module-level ints as constants)
NO_UPLIFT = int(Outcome.NO_UPLIFT)
SAFE = int(Outcome.SAFE)
OVERTURNED_WITHOUT_IMPACT = int(Outcome.OVERTURNED_WITHOUT_IMPACT)
OVERTURNED_AFTER_IMPACT = int(Outcome.OVERTURNED_AFTER_IMPACT)
UNDETERMINED = int(Outcome.UNDETERMINED)
