"""Fragility of each strategy over the record suite: stripes, lognormal MLE, median shift over FS."""
from rockstudy.analysis.fragility import fragility_dataset, fragility_markdown
from rockstudy.core import io
from rockstudy.model.control import Control
from rockstudy.model.records import read_record
from rockstudy.model.synthetic import MODEL_REFERENCE, ranges_from_dict
from rockstudy.studies import parameters, study

study.log_to(snakemake.log[0])
p = snakemake.params
scenario = parameters.scenario_from_dict(p.scenario)
records = [read_record(path, unit) for path, unit in zip(snakemake.input.records, p.units)]
suite = {"records": "files given in the config"}
if p.synthetic is not None:
    suite = {"records": "synthetic", "synthetic_model": MODEL_REFERENCE, "synthetic_seed": p.synthetic["seed"],
             **ranges_from_dict(p.synthetic).to_attrs()}
controls = [Control(s, sensor_band=scenario.control.sensor_band) for s in p.strategies]
ds = fragility_dataset(scenario.block, scenario.anchorage, controls, records,
                       parameters.intensity_levels(p.intensity_levels), measure=p.intensity_measure, n_boot=p.bootstrap,
                       seed=p.seed, overturn_criterion=scenario.overturn_criterion, free_time=scenario.free_time,
                       record_attrs=suite)
ds.attrs["rockstudy_source_sha256"] = p.library
io.write_netcdf(ds, snakemake.output.nc)
per_strategy = [name for name, var in ds.data_vars.items() if var.dims == ("strategy",)]
io.write_text(ds[per_strategy].to_dataframe().to_csv(float_format="%.5g"), snakemake.output.csv)
io.write_text(fragility_markdown(ds), snakemake.output.md)
