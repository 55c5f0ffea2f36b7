"""Overturning maps of the noise-free strategies: unsafe regions, safe islands, threshold."""
from rockstudy import plotting
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake)
    maps = job.read_all(snakemake.input)
    fig = plotting.figure_maps(maps, parameters.a_max0_ratio(maps[0], snakemake.params.a_max0))
    plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
