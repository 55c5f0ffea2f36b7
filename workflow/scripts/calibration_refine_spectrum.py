"""Device calibration: one spectrum of a best screened device with the study's full settings (40 realisations)."""
from rockstudy.core import io
from rockstudy.studies import device_calibration as calibration
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake, compiled=True)
    p, w = snakemake.params, snakemake.wildcards
    rank = int(w.rank)
    device, coarse_rms = calibration.best_devices(job.read(snakemake.input.grid), rank + 1)[rank]
    ds, = calibration.device_spectra(p.scenario, device, [w.strategy], {w.level: p.noise_level},
                                     parameters.frequency_ratios(p.frequency_grid), p.realisations,
                                     parameters.amplitude_grid(p.amplitude_grid))
    ds.attrs.update(calibration_rank=rank, coarse_rms_residual=coarse_rms)
    io.write_netcdf(job.stamp(ds), snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
