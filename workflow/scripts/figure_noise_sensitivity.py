"""Fig. 6: (a) convergence with the number of realisations; (b-d) FS, CS01, CS02 at each noise level."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import parameters, study

study.log_to(snakemake.log[0])
conv = io.read_netcdf(snakemake.input.convergence)
spectra = [io.read_netcdf(path) for path in snakemake.input.spectra]
fig = plotting.figure_noise_sensitivity(conv, spectra, parameters.a_max0_ratio(conv, snakemake.params.a_max0),
                                        panels=snakemake.params.panels)
plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)
