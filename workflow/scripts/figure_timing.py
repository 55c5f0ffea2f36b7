"""Figs. 7-8: overlapping thresholds for each sampling time T_s (or actuation delay)."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import parameters, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
p = snakemake.params
sweeps = [read_nc(path) for path in snakemake.input.sweep]
references = [read_nc(path) for path in snakemake.input.references]
fig = plotting.figure_timing(sweeps, p.variable, parameters.a_max0_ratio(sweeps[0], p.a_max0), p.paper_figure,
                             references)
plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)
