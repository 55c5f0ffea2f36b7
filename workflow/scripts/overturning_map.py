"""Overturning map (outcome at every grid point) of one noise-free strategy, with its threshold."""
import numba

from rockstudy.analysis.spectra import spectrum
from rockstudy.core import io
from rockstudy.studies import parameters, study

study.log_to(snakemake.log[0])
numba.set_num_threads(snakemake.threads)
p = snakemake.params
ds = spectrum(parameters.scenario_from_dict(p.scenario), parameters.frequency_ratios(p.frequency_grid),
              grid=parameters.amplitude_grid(p.amplitude_grid), with_map=True)
ds.attrs["rockstudy_source_sha256"] = p.library
io.write_netcdf(ds, snakemake.output[0])
