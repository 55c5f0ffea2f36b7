"""Device calibration: one spectrum of a best screened device with the study's full settings (40 realisations)."""
import numba

from rockstudy.core import io
from rockstudy.studies import device_calibration as calibration
from rockstudy.studies import parameters, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
numba.set_num_threads(snakemake.threads)
p, w = snakemake.params, snakemake.wildcards
rank = int(w.rank)
device, coarse_rms = calibration.best_devices(read_nc(snakemake.input.grid), rank + 1)[rank]
ds, = calibration.device_spectra(p.scenario, device, [w.strategy], {w.level: p.noise_level},
                                 parameters.frequency_ratios(p.frequency_grid), p.realisations,
                                 parameters.amplitude_grid(p.amplitude_grid))
ds.attrs.update(calibration_rank=rank, coarse_rms_residual=coarse_rms, rockstudy_source_sha256=p.library)
io.write_netcdf(ds, snakemake.output[0])
