"""Device calibration: the best screened devices recomputed with the study's full settings (40 realisations)."""
import numba

from rockstudy import calibration, io, study

study.log_to(snakemake.log[0])
numba.set_num_threads(snakemake.threads)
p = snakemake.params
grid = io.read_netcdf(snakemake.input.grid)
best = calibration.best_devices(grid, p.candidates)
devices, coarse = [d for d, _ in best], [rms for _, rms in best]
fs = [io.read_netcdf(f) for f in snakemake.input.fs]
tables = [calibration.device_table(fs, calibration.device_spectra(
    p.scenario, d, ["CS01", "CS02"], dict(p.levels), study.frequency_ratios(p.frequency_grid), p.realisations,
    study.amplitude_grid(p.amplitude_grid)), dict(p.levels), p.a_max0) for d in devices]
runtime = grid.attrs["compute_time_s"] + sum(t.attrs["compute_time_s"] for t in tables)
cands = calibration.candidates_dataset(study.block_from_dict(p.scenario["block"]), devices, tables, coarse,
                                       {"compute_time_s": runtime, "noise_reading": str(p.reading)})
io.write_netcdf(cands, snakemake.output.nc)
io.write_text(calibration.calibration_markdown(grid, cands, runtime), snakemake.output.md)
