"""Fig. 6: (a) convergence with the number of realisations; (b-d) FS, CS01, CS02 at each noise level."""
from rockstudy import plotting
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake)
    conv = job.read(snakemake.input.convergence)
    spectra = job.read_all(snakemake.input.spectra)
    fig = plotting.figure_noise_sensitivity(conv, spectra, parameters.a_max0_ratio(conv, snakemake.params.a_max0),
                                            panels=snakemake.params.panels)
    plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
