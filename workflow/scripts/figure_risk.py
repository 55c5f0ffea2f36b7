"""The risk of overturning on one record set: hazard curves, fragilities and disaggregation or scenarios."""
from rockstudy import plotting
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    plotting.save_figure(plotting.figure_risk(job.read(snakemake.input[0])), snakemake.output.png,
                         snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
