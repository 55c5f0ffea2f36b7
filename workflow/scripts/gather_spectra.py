"""Concatenate the realisation chunks of one spectrum and recompute a_min,OVER (min over realisations)."""
import numpy as np

from rockstudy.core import io
from rockstudy.studies import datasets, jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    ds = datasets.gather_spectra(job.read_all(snakemake.input))
    if list(ds["realisation"].values) != list(np.sort(snakemake.params.realisations)):
        raise ValueError(f"chunks hold realisations {ds['realisation'].values}, expected "
                         f"{snakemake.params.realisations}")
    io.write_netcdf(ds, snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
