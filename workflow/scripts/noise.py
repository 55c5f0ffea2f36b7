"""Noise realisations of one level: seeds, spawn keys, energy/PGA ratios, unit records (§5, Fig. 4)."""
from rockstudy.core import io
from rockstudy.studies import datasets, parameters, study

study.log_to(snakemake.log[0])
p = snakemake.params
ds = datasets.noise_dataset(parameters.scenario_from_dict(p.scenario), parameters.frequency_ratios(p.frequency_grid),
                         p.realisations, p.reference_frequency_ratio, p.n_records)
ds.attrs["rockstudy_source_sha256"] = p.library
io.write_netcdf(ds, snakemake.output[0])
