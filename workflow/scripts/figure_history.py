"""Figs. 2-3: normalised time history of the controlled block and the stiffness K."""
from rockstudy import plotting
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    fig = plotting.figure_control_history(job.read(snakemake.input[0]), snakemake.wildcards.fignum)
    plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
