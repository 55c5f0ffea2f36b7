"""Compile the engine once for the whole run, on a tiny case, into numba's on-disk cache, in three parts
(``params.part``): ``scan``, the step loop and then the threshold scan on a noisy record and on an analytic
excitation (what the spectra call); ``parts``, beside it, what the step loop, the driver and the scan call,
which ``scan`` then loads from the cache (``rockstudy.engine._kernel.parts``), and writes rockstudy's byte-code
for the jobs that follow (``jobs.write_bytecode``); ``more``, the rest the simulation jobs call (the
outcome map, a time history, and a scaled earthquake record's outcome and threshold scan called from
Python, as the fragility and design jobs do), which loads the scan's shared parts from the cache and runs
beside the first spectra. The jobs that follow load the compiled kernels instead of each compiling them."""
import dataclasses
import time

import numpy as np

from rockstudy.analysis.record_scan import RecordRun, record_threshold
from rockstudy.analysis.spectra import AmplitudeGrid, spectrum
from rockstudy.engine._kernel import parts
from rockstudy.model.records import Record
from rockstudy.studies import datasets, jobs, parameters


def main(snakemake):
    jobs.open_job(snakemake, compiled=True)
    start = time.process_time()
    noisy = parameters.scenario_from_dict(snakemake.params.scenario)
    free = dataclasses.replace(noisy, noise_level=0.0)
    grid = AmplitudeGrid(start=1.0, stop=1.2, step=0.1, resolution=0.05)
    part = snakemake.params.part
    if part == "scan":
        parts.compile_step_loop()  # first: meanwhile the rule compile_engine_parts compiles the rest it calls
        spectrum(noisy, [1.0], realisations=[0], grid=grid)
        spectrum(free, [1.0], grid=grid)
    elif part == "parts":
        parts.compile_driver_parts()
        jobs.write_bytecode()  # for the jobs that follow, should Python be told not to write it
    elif part == "more":
        spectrum(free, [1.0], grid=grid, with_map=True)
        datasets.time_history(noisy, 1.0, 1.1, 0)
        pulse = Record(name="one sine", dt=0.01, acceleration=np.sin(np.linspace(0.0, 2.0 * np.pi, 101)))
        record_threshold(RecordRun(free.block, free.anchorage, noisy.control, pulse), [1.0, 1.5], 0.25)
    else:
        raise ValueError(f"compile_engine: params.part is {part!r}; allowed: 'scan', 'parts', 'more'")
    seconds = time.process_time() - start
    with open(snakemake.output[0], "w") as f:
        f.write(f"rockstudy {snakemake.params.library}: {part} compiled in {seconds:.1f} s CPU\n")


if "snakemake" in globals():
    jobs.run(main, snakemake)
