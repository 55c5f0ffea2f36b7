"""Fig. 5: thresholds of two noise realisations and the rotation histories at "Ex01"."""
from rockstudy import plotting
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake)
    spectrum = job.read(snakemake.input.spectrum[0])
    point = {**snakemake.params.point, "a_max0_ratio": parameters.a_max0_ratio(spectrum, snakemake.params.a_max0)}
    fig = plotting.figure_realisations(spectrum, job.read_all(snakemake.input.histories), point)
    plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
