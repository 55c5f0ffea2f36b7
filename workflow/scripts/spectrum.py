"""Overturning spectra (§5, Figs. 5-8), one after the other in one process: a strategy's spectra at the
noise levels whose realisations fit one job (rule spectrum), a strategy's timing sweep (one spectrum per
sampling time or delay), or one chunk of noise realisations. The job is given one scenario per output
file, with its noise file and realisations (one for all, or one per scenario); a spectrum whose
realisations all fit in one job is written whole, as gathering its one chunk would write it."""
from rockstudy.analysis.spectra import spectrum
from rockstudy.core import io
from rockstudy.studies import datasets, jobs, parameters


def per_output(value, n: int, name: str, one) -> list:
    """``value`` as one item per output file: itself ``n`` times if ``one(value)``, else its items."""
    items = [value] * n if one(value) else list(value)
    if len(items) != n:
        raise ValueError(f"spectrum job: {len(items)} {name} for {n} output files")
    return items


def main(snakemake):
    job = jobs.open_job(snakemake, compiled=True)
    p = snakemake.params
    n = len(snakemake.output)
    specs = per_output(p.scenario, n, "scenarios", lambda v: isinstance(v, dict))
    noise_files = per_output(snakemake.input.noise, n, "noise files", lambda v: isinstance(v, str))
    realisations = per_output(p.realisations, n, "realisation lists",
                              lambda v: not v or not isinstance(v[0], (list, tuple)))
    scenarios = [parameters.scenario_from_dict(spec) for spec in specs]
    noises = {path: job.read(path) for path in dict.fromkeys(noise_files)}
    for scenario, path in zip(scenarios, noise_files):  # every scenario checked before the first simulation
        datasets.check_noise(noises[path], scenario)
    for scenario, reals, path in zip(scenarios, realisations, snakemake.output):
        ds = spectrum(scenario, parameters.frequency_ratios(p.frequency_grid), realisations=reals,
                      grid=parameters.amplitude_grid(p.amplitude_grid))
        datasets.document_missing(job.stamp(ds))
        if p.whole:
            ds = datasets.gather_spectra([ds])
        io.write_netcdf(ds, path)


if "snakemake" in globals():
    jobs.run(main, snakemake)
