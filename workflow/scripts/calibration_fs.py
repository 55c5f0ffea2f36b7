"""Device calibration, screening: the FS reference spectra on the coarse grid with few realisations."""
from rockstudy.analysis.spectra import spectrum
from rockstudy.core import io
from rockstudy.studies import jobs, parameters


def main(snakemake):
    jobs.open_job(snakemake, compiled=True)
    p = snakemake.params
    for spec, path in zip(p.scenarios, snakemake.output):
        ds = spectrum(parameters.scenario_from_dict(spec), parameters.frequency_ratios(p.frequency_grid),
                      realisations=range(p.realisations if spec["noise_level"] > 0 else 1),
                      grid=parameters.amplitude_grid(p.amplitude_grid))
        io.write_netcdf(ds, path)


if "snakemake" in globals():
    jobs.run(main, snakemake)
