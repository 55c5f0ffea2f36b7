"""Records scaled up until they overturn the block: outcomes on a grid of scales and the threshold scan.

A record is scaled by its peak ground acceleration: the amplitude ratio of a scaled record is
PGA/(g·tanα), as for the paper's excitations (a_p/(g·tanα)). The outcome at every level of a
grid comes from the compiled engine (with its energy bound: a run ends once it provably cannot
overturn any more, which never changes an outcome). The **threshold** of a record is found with
the overturning spectra's rules (:mod:`rockstudy.engine._kernel.scan`, the same state machine):
an upward scan of the grid, then a bisection between the last safe and the first overturning
grid level down to a resolution. Every grid level below the threshold has been shown safe (a level
where the record cannot even uplift the block, PGA <= g·tanα, is safe without a run); levels
above it may hold safe islands.
"""
from __future__ import annotations

import numpy as np

from rockstudy.core import validation
from rockstudy.core.quantities import check_arguments, declares
from rockstudy.engine import _kernel
from rockstudy.engine._kernel.scan import S_J, S_PHASE, SCANNING
from rockstudy.engine.outcome import NO_UPLIFT, OVERTURNED_AFTER_IMPACT, OVERTURNED_WITHOUT_IMPACT, UNDETERMINED
from rockstudy.engine.simulate import DEFAULT_FREE_TIME, kernel_record, pack_parameters
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import Block
from rockstudy.model.control import Control
from rockstudy.model.records import Record


def unit_peak_record(record: Record) -> Record:
    """The record divided by its PGA (peak 1), so that a scale equals the scaled PGA. [-]

    Parameters
    ----------
    record : Record
        The record, with a PGA > 0.
    """
    return Record(name=record.name, dt=record.dt, acceleration=record.acceleration / record.pga,
                  source=record.source, unit="1")


class RecordRun:
    """A block, anchorage and control under one record, ready to run at any amplitude ratio.

    Parameters
    ----------
    block, anchorage, control : rockstudy.Block, rockstudy.Anchorage, rockstudy.Control
        The block, its restrainers and the control strategy.
    record : Record
        The unscaled record; it is run divided by its PGA.
    overturn_criterion, free_time : {"flat", "alpha"}, float
        As for :func:`rockstudy.engine.simulate.simulate` (free time in [s]).
    """

    def __init__(self, block: Block, anchorage: Anchorage, control: Control, record: Record, *,
                 overturn_criterion: str = "flat", free_time: float = DEFAULT_FREE_TIME):
        self.block, self.record = block, record
        motion = unit_peak_record(record).motion(1.0)
        self.P = pack_parameters(block, anchorage, control, motion, overturn_criterion=overturn_criterion,
                                 free_time=free_time, energy_bound=True)
        self.samples = _kernel.writable(kernel_record(control, motion))
        self.vertical = np.zeros(0)

    def outcome(self, amplitude_ratio: float) -> int:
        """:class:`~rockstudy.engine.outcome.Outcome` code of the record scaled to PGA/(g·tanα) = amplitude_ratio.

        Parameters
        ----------
        amplitude_ratio : float
            PGA of the scaled record over g·tanα. [-]
        """
        return int(_kernel.outcome_kernel(self.P, self.samples, self.vertical, float(amplitude_ratio), 1.0))

    def scale(self, amplitude_ratio) -> np.ndarray:
        """Factor on the record that gives it PGA/(g·tanα) = amplitude_ratio. [-]

        Parameters
        ----------
        amplitude_ratio : float or array_like
            PGA of the scaled record over g·tanα. [-]
        """
        return np.asarray(amplitude_ratio, dtype=float) * self.block.uplift_acceleration / self.record.pga


def is_overturned(code) -> np.ndarray:
    """Whether outcome codes are overturned (with or without impact).

    Parameters
    ----------
    code : int or array_like of int
        :class:`~rockstudy.engine.outcome.Outcome` codes.
    """
    return np.isin(np.asarray(code), (OVERTURNED_WITHOUT_IMPACT, OVERTURNED_AFTER_IMPACT))


@declares(resolution="amplitude_resolution")
def record_threshold(run: RecordRun, grid, resolution: float, outcomes=None) -> dict:
    """Smallest amplitude ratio PGA/(g·tanα) that overturns the block under the scaled record.

    Parameters
    ----------
    run : RecordRun
        The block, anchorage, control and record to run.
    grid : array_like
        Increasing amplitude ratios scanned upward. [-]
    resolution : float
        Width of the final bracket. [-]
    outcomes : array_like of int, optional
        Outcome codes already known at the grid levels (from :func:`grid_outcomes`); runs only the bisection.

    Returns
    -------
    dict
        ``amplitude_ratio`` (NaN: nothing on the grid overturns), ``last_safe_amplitude_ratio`` (every
        grid level below it was shown safe), ``n_simulations`` and ``n_undetermined`` (runs at the
        engine's event cap, counted as not overturned).
    """
    resolution = check_arguments("record_threshold", {"resolution": resolution})["resolution"]
    grid = np.asarray(grid, dtype=float)
    if grid.ndim != 1 or grid.size < 1 or np.any(np.diff(grid) <= 0) or np.any(grid <= 0):
        raise ValueError("grid must be an increasing 1-D list of positive amplitude ratios")
    state, n_sim, n_und = _kernel.scan_start(), 0, 0
    done = False
    while not done:
        amplitude = float(_kernel.scan_amplitude(state, grid))
        known = outcomes is not None and state[S_PHASE] == SCANNING
        code = int(outcomes[int(state[S_J])]) if known else run.outcome(amplitude)
        if not known:
            n_sim += code != NO_UPLIFT
            n_und += code == UNDETERMINED
        done = _kernel.scan_update(state, grid, float(resolution), 1.0, bool(is_overturned(code)))
    return {"amplitude_ratio": float(state[_kernel.S_HI]), "last_safe_amplitude_ratio": float(state[_kernel.S_LO]),
            "n_simulations": int(n_sim), "n_undetermined": int(n_und)}


def grid_outcomes(run: RecordRun, grid) -> np.ndarray:
    """Outcome codes of the record scaled to each amplitude ratio of ``grid`` (int8).

    Parameters
    ----------
    run : RecordRun
        The block, anchorage, control and record to run.
    grid : array_like
        Amplitude ratios PGA/(g·tanα), one run each. [-]
    """
    return np.array([run.outcome(a) for a in np.asarray(grid, dtype=float)], dtype=np.int8)


def stripes_and_thresholds(block: Block, anchorage: Anchorage, controls, records, levels, intensities, *,
                           resolution: float, overturn_criterion: str = "flat",
                           free_time: float = DEFAULT_FREE_TIME):
    """Outcomes of every (control, record, level) and every record's threshold, one scan per pair.

    Parameters
    ----------
    block, anchorage : rockstudy.Block, rockstudy.Anchorage
        The block and its restrainers.
    controls : sequence of Control
        The strategies (with their timing).
    records : sequence of Record
        The unscaled records.
    levels : array_like
        Intensity levels x_j (increasing). [IM]
    intensities : array_like
        Intensity of each unscaled record, in the unit of ``levels``. [IM]
    resolution : float
        Resolution of the thresholds, in the unit of ``levels``. [IM]
    overturn_criterion, free_time : {"flat", "alpha"}, float
        As for :func:`rockstudy.engine.simulate.simulate` (free time in [s]).

    Returns
    -------
    dict of ndarray
        ``outcome`` (control, record, level) codes; ``scale`` (record, level) factors on the records;
        ``threshold`` and ``last_safe`` (control, record) in the unit of ``levels`` (NaN: no overturning
        on the grid); ``n_simulations`` (control, record).
    """
    validation.check_items("controls", controls, what="control")
    validation.check_items("records", records, what="record")
    validation.check_items("levels", levels, what="level")
    levels = np.asarray(levels, dtype=float)
    intensities = np.asarray(intensities, dtype=float)
    shape = (len(controls), len(records))
    outcome = np.zeros(shape + (levels.size,), dtype=np.int8)
    thr, low = np.full(shape, np.nan), np.full(shape, np.nan)
    nsim = np.zeros(shape, dtype=np.int64)
    scale = np.zeros((len(records), levels.size))
    for r, record in enumerate(records):
        # the record's PGA ratio per unit of the intensity measure (1 for PGA/(g tan alpha))
        per_level = record.pga / block.uplift_acceleration / intensities[r]
        scale[r] = levels / intensities[r]
        for c, control in enumerate(controls):
            run = RecordRun(block, anchorage, control, record, overturn_criterion=overturn_criterion,
                            free_time=free_time)
            outcome[c, r] = grid_outcomes(run, levels * per_level)
            res = record_threshold(run, levels * per_level, resolution * per_level, outcome[c, r])
            thr[c, r] = res["amplitude_ratio"] / per_level
            low[c, r] = res["last_safe_amplitude_ratio"] / per_level
            nsim[c, r] = int(np.sum(outcome[c, r] != NO_UPLIFT)) + res["n_simulations"]
    return {"outcome": outcome, "scale": scale, "threshold": thr, "last_safe": low, "n_simulations": nsim}
