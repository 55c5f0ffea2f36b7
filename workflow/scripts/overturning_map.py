"""Overturning map (outcome at every grid point) of one noise-free strategy, with its threshold."""
import numba

from rockstudy import io, study
from rockstudy.spectra import spectrum

study.log_to(snakemake.log[0])
numba.set_num_threads(snakemake.threads)
p = snakemake.params
ds = spectrum(study.scenario_from_dict(p.scenario), study.frequency_ratios(p.frequency_grid),
              grid=study.amplitude_grid(p.amplitude_grid), with_map=True)
ds.attrs["rockstudy_source_sha256"] = p.library
io.write_netcdf(ds, snakemake.output[0])
