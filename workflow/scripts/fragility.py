"""Fragility of each strategy over one record set: stripes, lognormal MLE, median shift over FS, and every
record's threshold (the smallest scale that overturns the block)."""
from rockstudy.analysis.fragility import suite_fragility_dataset
from rockstudy.core import io
from rockstudy.model.control import Control
from rockstudy.model.record_suites import entries_from_dataset
from rockstudy.report import fragility_markdown, threshold_markdown
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake)
    entries = entries_from_dataset(job.read(snakemake.input.records))  # the record set checked first
    p = snakemake.params
    scenario = parameters.scenario_from_dict(p.scenario)
    controls = [Control(s, sensor_band=scenario.control.sensor_band) for s in p.strategies]
    ds = suite_fragility_dataset(scenario.block, scenario.anchorage, controls, entries,
                                 parameters.intensity_levels(p.intensity_levels), suite=snakemake.wildcards.recordset,
                                 measure=p.intensity_measure, resolution=p.threshold_resolution, n_boot=p.bootstrap,
                                 seed=p.seed, overturn_criterion=scenario.overturn_criterion,
                                 free_time=scenario.free_time)
    io.write_netcdf(job.stamp(ds), snakemake.output.nc)
    per_strategy = [name for name, var in ds.data_vars.items() if var.dims == ("strategy",)]
    io.write_text(ds[per_strategy].to_dataframe().to_csv(float_format="%.5g"), snakemake.output.csv)
    io.write_text(fragility_markdown(ds), snakemake.output.md)
    per_record = ["threshold_intensity", "last_safe_intensity", "threshold_scale", "threshold_pga"]
    table = ds[per_record].to_dataframe().reset_index()  # with the records' catalogue (coordinates)
    io.write_text(table.to_csv(index=False, float_format="%.5g"), snakemake.output.thresholds_csv)
    io.write_text(threshold_markdown(ds), snakemake.output.thresholds_md)


if "snakemake" in globals():
    jobs.run(main, snakemake)
