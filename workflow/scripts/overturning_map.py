"""Overturning map (outcome at every grid point) of one noise-free strategy, with its threshold."""
from rockstudy.analysis.spectra import spectrum
from rockstudy.core import io
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake, compiled=True)
    p = snakemake.params
    ds = spectrum(parameters.scenario_from_dict(p.scenario), parameters.frequency_ratios(p.frequency_grid),
                  grid=parameters.amplitude_grid(p.amplitude_grid), with_map=True)
    io.write_netcdf(job.stamp(ds), snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
