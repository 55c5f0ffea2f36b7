"""Figs. 7-8: overlapping thresholds for each sampling time T_s (or actuation delay)."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import parameters, study

study.log_to(snakemake.log[0])
p = snakemake.params
sweeps = [io.read_netcdf(path) for path in snakemake.input.sweep]
references = [io.read_netcdf(path) for path in snakemake.input.references]
fig = plotting.figure_timing(sweeps, p.variable, parameters.a_max0_ratio(sweeps[0], p.a_max0), p.paper_figure,
                             references)
plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)
