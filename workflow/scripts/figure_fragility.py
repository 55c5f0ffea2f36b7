"""Fragility curves over the record suite and the median shift of each device over FS."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
plotting.save_figure(plotting.figure_fragility(read_nc(snakemake.input[0])), snakemake.output.png,
                     snakemake.output.pdf)
