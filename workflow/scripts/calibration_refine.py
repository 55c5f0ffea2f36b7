"""Device calibration: the best screened devices with the study's full settings - 12 residuals, K_max, D."""
from rockstudy.core import io
from rockstudy.studies import device_calibration as calibration
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake)
    p = snakemake.params
    grid = job.read(snakemake.input.grid)
    best = calibration.best_devices(grid, p.candidates)
    fs = job.read_all(snakemake.input.fs)
    spectra = job.read_all(snakemake.input.spectra)
    tables = [calibration.device_table(fs, [ds for ds in spectra if ds.attrs["calibration_rank"] == rank],
                                       dict(p.levels), p.a_max0) for rank in range(len(best))]
    runtime = grid.attrs["compute_time_s"] + sum(t.attrs["compute_time_s"] for t in tables)
    cands = calibration.candidates_dataset(parameters.block_from_dict(p.block), [d for d, _ in best], tables,
                                           [rms for _, rms in best],
                                           {"compute_time_s": runtime, "noise_reading": str(p.reading)})
    io.write_netcdf(cands, snakemake.output.nc)
    io.write_text(calibration.calibration_markdown(grid, cands, runtime), snakemake.output.md)


if "snakemake" in globals():
    jobs.run(main, snakemake)
