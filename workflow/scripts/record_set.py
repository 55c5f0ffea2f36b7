"""One record set of the fragility study (a suite, or the SUITE:ID names and files listed) as a netCDF file
with every record's samples and catalogue (suite, id, event, station, ...)."""
from rockstudy.core import io
from rockstudy.model.record_suites import suite_dataset
from rockstudy.studies import beyond, jobs
from rockstudy.studies.expectations import record_set_members


def main(snakemake):
    job = jobs.open_job(snakemake)
    p, name = snakemake.params, snakemake.wildcards.recordset
    ds = suite_dataset(beyond.set_entries(p.members, p.synthetic), title=f"Record set {name} of the fragility study")
    ds.attrs.update(record_set=name, record_set_members=record_set_members(p.members))
    io.write_netcdf(job.stamp(ds), snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
