"""The readings study: FS row of Table 1 under each reading of the noise model, against the paper."""
from rockstudy.core import io
from rockstudy.studies import noise_readings as readings
from rockstudy.studies import parameters, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
p = snakemake.params
spectra = {key: read_nc(path) for key, path in zip(p.spectrum_keys, snakemake.input.spectra)}
table = readings.readings_table(spectra, read_nc(snakemake.input.reference),
                                {name: parameters.reading_from_dict(spec) for name, spec in p.readings.items()},
                                dict(p.levels), p.a_max0)
io.write_netcdf(table, snakemake.output.nc)
io.write_text(readings.readings_csv(table), snakemake.output.csv)
io.write_text(readings.readings_markdown(table), snakemake.output.md)
