"""The map of the probability of overturning per strategy at every site of the config's hazard files."""
from rockstudy import plotting
from rockstudy.plotting.sites import figure_risk_sites
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    plotting.save_figure(figure_risk_sites(job.read(snakemake.input[0])), snakemake.output.png,
                         snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
