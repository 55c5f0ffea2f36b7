"""Fig. 6a data: a_min,OVER over the first N noise realisations, N = 1 ... n."""
from rockstudy.core import io
from rockstudy.studies import datasets, jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    ds = job.read(snakemake.input[0])
    io.write_netcdf(datasets.convergence_dataset(ds), snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
