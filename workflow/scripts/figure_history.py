"""Figs. 2-3: normalised time history of the controlled block and the stiffness K."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
fig = plotting.figure_control_history(read_nc(snakemake.input[0]), snakemake.wildcards.fignum)
plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)
