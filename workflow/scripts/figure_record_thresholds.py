"""Every record's threshold per strategy: which records overturn the block with which device."""
from rockstudy import plotting
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    plotting.save_figure(plotting.figure_record_thresholds(job.read(snakemake.input[0])), snakemake.output.png,
                         snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
