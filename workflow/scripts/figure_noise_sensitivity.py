"""Fig. 6: (a) convergence with the number of realisations; (b-d) FS, CS01, CS02 at each noise level."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import parameters, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
conv = read_nc(snakemake.input.convergence)
spectra = [read_nc(path) for path in snakemake.input.spectra]
fig = plotting.figure_noise_sensitivity(conv, spectra, parameters.a_max0_ratio(conv, snakemake.params.a_max0),
                                        panels=snakemake.params.panels)
plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)
