"""Time history of one (strategy, noise realisation, frequency, amplitude) case (Figs. 2, 3, 5b)."""
from rockstudy.core import io
from rockstudy.studies import datasets, jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake)
    p = snakemake.params
    ds = datasets.time_history(parameters.scenario_from_dict(p.scenario), p.frequency_ratio, p.amplitude_ratio,
                               p.realisation)
    io.write_netcdf(job.stamp(ds), snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
