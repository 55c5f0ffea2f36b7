"""FS overturning spectrum under one reading of the noise model, all realisations in one job (readings study)."""
import numba

from rockstudy.analysis.spectra import spectrum
from rockstudy.core import io
from rockstudy.studies import parameters, study

study.log_to(snakemake.log[0])
numba.set_num_threads(snakemake.threads)
p = snakemake.params
scenario = parameters.scenario_from_dict(p.scenario)
ds = spectrum(scenario, parameters.frequency_ratios(p.frequency_grid), realisations=range(p.realisations),
              grid=parameters.amplitude_grid(p.amplitude_grid))
ds.attrs.update(rockstudy_source_sha256=p.library, noise_reading_name=snakemake.wildcards.reading)
io.write_netcdf(ds, snakemake.output[0])
