"""Overturning spectrum of one chunk of noise realisations (§5, Figs. 5-8); a spectrum whose realisations
all fit in one job is written whole, as gathering its one chunk would write it. A timing sweep's job is
given a list of scenarios, one per output file, and writes them one after the other."""
from rockstudy.analysis.spectra import spectrum
from rockstudy.core import io
from rockstudy.studies import datasets, jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake, compiled=True)
    p = snakemake.params
    specs = p.scenario if isinstance(p.scenario, list) else [p.scenario]
    if len(specs) != len(snakemake.output):
        raise ValueError(f"spectrum job: {len(specs)} scenarios for {len(snakemake.output)} output files")
    scenarios = [parameters.scenario_from_dict(spec) for spec in specs]
    noise = job.read(snakemake.input.noise)
    for scenario in scenarios:  # every scenario checked before the first simulation
        datasets.check_noise(noise, scenario)
    for scenario, path in zip(scenarios, snakemake.output):
        ds = spectrum(scenario, parameters.frequency_ratios(p.frequency_grid), realisations=p.realisations,
                      grid=parameters.amplitude_grid(p.amplitude_grid))
        datasets.document_missing(job.stamp(ds))
        if p.whole:
            ds = datasets.gather_spectra([ds])
        io.write_netcdf(ds, path)


if "snakemake" in globals():
    main(snakemake)
