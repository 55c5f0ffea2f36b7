"""Device calibration, screening: Table 1 of one device on the coarse grid with few realisations."""
import numba

from rockstudy.core import io
from rockstudy.studies import device_calibration as calibration
from rockstudy.studies import parameters, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
numba.set_num_threads(snakemake.threads)
p = snakemake.params
spectra = calibration.device_spectra(p.scenario, p.anchorage, ["CS01", "CS02"], dict(p.levels),
                                     parameters.frequency_ratios(p.frequency_grid), p.realisations,
                                     parameters.amplitude_grid(p.amplitude_grid))
table = calibration.device_table([read_nc(f) for f in snakemake.input.fs], spectra, dict(p.levels), p.a_max0)
table.attrs.update({f"anchorage_{k}": v for k, v in p.anchorage.items()})
io.write_netcdf(table, snakemake.output[0])
