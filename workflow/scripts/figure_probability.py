"""P(overturn) surfaces over the noise realisations, laid out like the overturning maps."""
from rockstudy import plotting
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake)
    surfaces = job.read_all(snakemake.input)
    fig = plotting.figure_probability(surfaces, parameters.a_max0_ratio(surfaces[0], snakemake.params.a_max0))
    plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
