"""Device calibration, screening: Table 1 of one device on the coarse grid with few realisations."""
import numba

from rockstudy import calibration, io, study

study.log_to(snakemake.log[0])
numba.set_num_threads(snakemake.threads)
p = snakemake.params
spectra = calibration.device_spectra(p.scenario, p.anchorage, ["CS01", "CS02"], dict(p.levels),
                                     study.frequency_ratios(p.frequency_grid), p.realisations,
                                     study.amplitude_grid(p.amplitude_grid))
table = calibration.device_table([io.read_netcdf(f) for f in snakemake.input.fs], spectra, dict(p.levels), p.a_max0)
table.attrs.update({f"anchorage_{k}": v for k, v in p.anchorage.items()})
io.write_netcdf(table, snakemake.output[0])
