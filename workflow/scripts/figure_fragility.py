"""Fragility curves over the record suite and the median shift of each device over FS."""
from rockstudy import plotting
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    plotting.save_figure(plotting.figure_fragility(job.read(snakemake.input[0])), snakemake.output.png,
                         snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
