"""Overturning maps of the noise-free strategies: unsafe regions, safe islands, threshold."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import parameters, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
maps = [read_nc(path) for path in snakemake.input]
fig = plotting.figure_maps(maps, parameters.a_max0_ratio(maps[0], snakemake.params.a_max0))
plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)
