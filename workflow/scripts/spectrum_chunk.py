"""Overturning spectrum of one chunk of noise realisations (§5, Figs. 5-8)."""
import numba

from rockstudy import datasets, io, study
from rockstudy.spectra import spectrum

study.log_to(snakemake.log[0])
numba.set_num_threads(snakemake.threads)
p = snakemake.params
scenario = study.scenario_from_dict(p.scenario)
datasets.check_noise(io.read_netcdf(snakemake.input.noise), scenario)
ds = spectrum(scenario, study.frequency_ratios(p.frequency_grid), realisations=p.realisations,
              grid=study.amplitude_grid(p.amplitude_grid))
datasets.document_missing(ds)
ds.attrs["rockstudy_source_sha256"] = p.library
io.write_netcdf(ds, snakemake.output[0])
