"""Figs. 7-8: overlapping thresholds for each sampling time T_s (or actuation delay)."""
from rockstudy import plotting
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake)
    p = snakemake.params
    sweeps = job.read_all(snakemake.input.sweep)
    references = job.read_all(snakemake.input.references)
    fig = plotting.figure_timing(sweeps, p.variable, parameters.a_max0_ratio(sweeps[0], p.a_max0), p.paper_figure,
                                 references)
    plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
