"""Figure of the readings study: FS J_OS against noise level per reading, the paper's values as markers."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
plotting.save_figure(plotting.figure_readings(read_nc(snakemake.input[0])), snakemake.output.png,
                     snakemake.output.pdf)
