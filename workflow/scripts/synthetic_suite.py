"""The synthetic record suite: one PEER .AT2 file per record and a netCDF file with the model parameters."""
from rockstudy.core import io
from rockstudy.model.records import write_at2
from rockstudy.model.synthetic import ranges_from_dict, suite_dataset, synthetic_suite
from rockstudy.studies import jobs


def main(snakemake):
    jobs.open_job(snakemake)
    spec = snakemake.params.synthetic
    ranges = ranges_from_dict(spec)
    suite = synthetic_suite(spec["n_records"], spec["seed"], ranges)
    for (record, _), path in zip(suite, snakemake.output.records):
        write_at2(record, path, title=f"rockstudy synthetic record (Kanai-Tajimi/Clough-Penzien noise, "
                                      f"Saragoni-Hart envelope), seed {spec['seed']}")
    io.write_netcdf(suite_dataset(suite, spec["seed"], ranges), snakemake.output.nc)


if "snakemake" in globals():
    jobs.run(main, snakemake)
