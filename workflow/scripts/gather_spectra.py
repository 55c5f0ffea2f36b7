"""Concatenate the realisation chunks of one spectrum and recompute a_min,OVER (min over realisations)."""
import numpy as np

from rockstudy.core import io
from rockstudy.studies import datasets, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
ds = datasets.gather_spectra([read_nc(path) for path in snakemake.input])
if list(ds["realisation"].values) != list(np.sort(snakemake.params.realisations)):
    raise ValueError(f"chunks hold realisations {ds['realisation'].values}, expected {snakemake.params.realisations}")
io.write_netcdf(ds, snakemake.output[0])
