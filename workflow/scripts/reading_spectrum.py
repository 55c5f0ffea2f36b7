"""FS overturning spectrum under one reading of the noise model, all realisations in one job (readings study)."""
from rockstudy.analysis.spectra import spectrum
from rockstudy.core import io
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake, compiled=True)
    p = snakemake.params
    scenario = parameters.scenario_from_dict(p.scenario)
    ds = spectrum(scenario, parameters.frequency_ratios(p.frequency_grid), realisations=range(p.realisations),
                  grid=parameters.amplitude_grid(p.amplitude_grid))
    ds.attrs.update(noise_reading_name=snakemake.wildcards.reading)
    io.write_netcdf(job.stamp(ds), snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
