"""Time history of one (strategy, noise realisation, frequency, amplitude) case (Figs. 2, 3, 5b)."""
from rockstudy.core import io
from rockstudy.studies import datasets, parameters, study

study.log_to(snakemake.log[0])
p = snakemake.params
ds = datasets.time_history(parameters.scenario_from_dict(p.scenario), p.frequency_ratio, p.amplitude_ratio,
                           p.realisation)
ds.attrs["rockstudy_source_sha256"] = p.library
io.write_netcdf(ds, snakemake.output[0])
