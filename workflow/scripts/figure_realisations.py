"""Fig. 5: thresholds of two noise realisations and the rotation histories at "Ex01"."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import parameters, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
spectrum = read_nc(snakemake.input.spectrum[0])
point = {**snakemake.params.point, "a_max0_ratio": parameters.a_max0_ratio(spectrum, snakemake.params.a_max0)}
fig = plotting.figure_realisations(spectrum, [read_nc(p) for p in snakemake.input.histories], point)
plotting.save_figure(fig, snakemake.output.png, snakemake.output.pdf)
