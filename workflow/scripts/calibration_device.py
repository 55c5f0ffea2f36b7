"""Device calibration, screening: Table 1 of one device on the coarse grid with few realisations."""
from rockstudy.core import io
from rockstudy.studies import device_calibration as calibration
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake, compiled=True)
    p = snakemake.params
    spectra = calibration.device_spectra(p.scenario, p.anchorage, ["CS01", "CS02"], dict(p.levels),
                                         parameters.frequency_ratios(p.frequency_grid), p.realisations,
                                         parameters.amplitude_grid(p.amplitude_grid))
    table = calibration.device_table(job.read_all(snakemake.input.fs), spectra, dict(p.levels), p.a_max0)
    table.attrs.update({f"anchorage_{k}": v for k, v in p.anchorage.items()})
    io.write_netcdf(table, snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
