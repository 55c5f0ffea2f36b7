"""The risk of overturning on one record set: hazard curves, fragilities and disaggregation or scenarios."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
plotting.save_figure(plotting.figure_risk(read_nc(snakemake.input[0])), snakemake.output.png,
                     snakemake.output.pdf)
