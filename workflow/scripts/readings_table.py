"""The readings study: FS row of Table 1 under each reading of the noise model, against the paper."""
from rockstudy.core import io
from rockstudy.studies import jobs, parameters
from rockstudy.studies import noise_readings as readings


def main(snakemake):
    job = jobs.open_job(snakemake)
    p = snakemake.params
    spectra = {key: job.read(path) for key, path in zip(p.spectrum_keys, snakemake.input.spectra)}
    table = readings.readings_table(spectra, job.read(snakemake.input.reference),
                                    {name: parameters.reading_from_dict(spec) for name, spec in p.readings.items()},
                                    dict(p.levels), p.a_max0)
    io.write_netcdf(table, snakemake.output.nc)
    io.write_text(readings.readings_csv(table), snakemake.output.csv)
    io.write_text(readings.readings_markdown(table), snakemake.output.md)


if "snakemake" in globals():
    jobs.run(main, snakemake)
