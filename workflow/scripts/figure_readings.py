"""Figure of the readings study: FS J_OS against noise level per reading, the paper's values as markers."""
from rockstudy import plotting
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    plotting.save_figure(plotting.figure_readings(job.read(snakemake.input[0])), snakemake.output.png,
                         snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
