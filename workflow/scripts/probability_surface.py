"""P(overturn) at every (omega_p/p, a_p/(g tan alpha)) point over the noise realisations (Eq. P1)."""
import numba

from rockstudy.analysis.probability import probability_surface
from rockstudy.core import io
from rockstudy.studies import datasets, parameters, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
numba.set_num_threads(snakemake.threads)
p = snakemake.params
scenario = parameters.scenario_from_dict(p.scenario)
datasets.check_noise(read_nc(snakemake.input.noise), scenario)
ds = probability_surface(scenario, parameters.frequency_ratios(p.frequency_grid, "beyond.probability.frequency_grid"),
                         realisations=range(p.realisations),
                         grid=parameters.amplitude_grid(p.amplitude_grid, "beyond.probability.amplitude_grid"))
ds.attrs["rockstudy_source_sha256"] = p.library
io.write_netcdf(ds, snakemake.output[0])
