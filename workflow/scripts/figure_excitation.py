"""Fig. 4: baseline Eq. 23 excitation and the same contaminated with noise."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
fig = plotting.figure_excitation(read_nc(snakemake.input[0]))
plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)
