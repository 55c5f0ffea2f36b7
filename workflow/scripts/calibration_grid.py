"""Device calibration: the screened grid (J_OS maps, residuals, ranking share) and its figure."""
from rockstudy import plotting
from rockstudy.core import io
from rockstudy.studies import device_calibration as calibration
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    p = snakemake.params
    design = calibration.CalibrationDesign(**p.design)
    tables = job.read_all(snakemake.input)
    attrs = {"compute_time_s": sum(t.attrs["compute_time_s"] for t in tables), "noise_reading": str(p.reading)}
    grid = calibration.grid_dataset(design, tables, p.alpha, attrs)
    io.write_netcdf(grid, snakemake.output.nc)
    best, _ = calibration.best_devices(grid, 1)[0]
    plotting.save_figure(plotting.figure_calibration(grid, best), snakemake.output.png, snakemake.output.pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
