"""One record set of the fragility study (a suite, or the SUITE:ID names and files listed) as a netCDF file
with every record's samples and catalogue (suite, id, event, station, ...)."""
from rockstudy.core import io
from rockstudy.model.record_suites import suite_dataset
from rockstudy.studies import beyond, study

study.log_to(snakemake.log[0])
p = snakemake.params
entries = beyond.set_entries(p.members, p.synthetic)
ds = suite_dataset(entries, title=f"Record set {snakemake.wildcards.recordset} of the fragility study")
ds.attrs["rockstudy_source_sha256"] = p.library
io.write_netcdf(ds, snakemake.output[0])
