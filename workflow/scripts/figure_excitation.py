"""Fig. 4: baseline Eq. 23 excitation and the same contaminated with noise."""
from rockstudy import plotting
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    fig = plotting.figure_excitation(job.read(snakemake.input[0]))
    plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
