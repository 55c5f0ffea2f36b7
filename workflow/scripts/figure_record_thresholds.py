"""Every record's threshold per strategy: which records overturn the block with which device."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import study

study.log_to(snakemake.log[0])
plotting.save_figure(plotting.figure_record_thresholds(io.read_netcdf(snakemake.input[0])), snakemake.output.png,
                     snakemake.output.pdf)
