"""Noise realisations of one level: seeds, spawn keys, energy/PGA ratios, unit records (§5, Fig. 4)."""
from rockstudy.core import io
from rockstudy.studies import datasets, jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake)
    p = snakemake.params
    ds = datasets.noise_dataset(parameters.scenario_from_dict(p.scenario),
                                parameters.frequency_ratios(p.frequency_grid), p.realisations,
                                p.reference_frequency_ratio, p.n_records)
    io.write_netcdf(job.stamp(ds), snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
