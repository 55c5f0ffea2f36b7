"""Fragility curves over the record suite and the median shift of each device over FS."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import study

study.log_to(snakemake.log[0])
plotting.save_figure(plotting.figure_fragility(io.read_netcdf(snakemake.input[0])), snakemake.output.png,
                     snakemake.output.pdf)
