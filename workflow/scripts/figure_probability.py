"""P(overturn) surfaces over the noise realisations, laid out like the overturning maps."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import parameters, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
surfaces = [read_nc(path) for path in snakemake.input]
fig = plotting.figure_probability(surfaces, parameters.a_max0_ratio(surfaces[0], snakemake.params.a_max0))
plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)
