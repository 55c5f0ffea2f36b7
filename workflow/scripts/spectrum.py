"""Overturning spectrum of one chunk of noise realisations (§5, Figs. 5-8); a spectrum whose realisations
all fit in one job is written whole, as gathering its one chunk would write it. A timing sweep's job is
given a list of scenarios, one per output file, and writes them one after the other."""
import numba

from rockstudy.analysis.spectra import spectrum
from rockstudy.core import io
from rockstudy.studies import datasets, parameters, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
numba.set_num_threads(snakemake.threads)
p = snakemake.params
specs = p.scenario if isinstance(p.scenario, list) else [p.scenario]
if len(specs) != len(snakemake.output):
    raise ValueError(f"spectrum job: {len(specs)} scenarios for {len(snakemake.output)} output files")
scenarios = [parameters.scenario_from_dict(spec) for spec in specs]
noise = read_nc(snakemake.input.noise)
for scenario in scenarios:  # every scenario checked before the first simulation
    datasets.check_noise(noise, scenario)
for scenario, path in zip(scenarios, snakemake.output):
    ds = spectrum(scenario, parameters.frequency_ratios(p.frequency_grid), realisations=p.realisations,
                  grid=parameters.amplitude_grid(p.amplitude_grid))
    datasets.document_missing(ds)
    ds.attrs["rockstudy_source_sha256"] = p.library
    if p.whole:
        ds = datasets.gather_spectra([ds])
    io.write_netcdf(ds, path)
