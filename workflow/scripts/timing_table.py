"""J_OS of the sampling (or delay) sweep against the same strategy without it and against FS (§5.2)."""
from rockstudy.core import io
from rockstudy.studies import jobs, tables


def main(snakemake):
    job = jobs.open_job(snakemake)
    p, i = snakemake.params, snakemake.input
    table = tables.timing_table(job.read_all(i.sweep), job.read_all(i.same_strategy), job.read_all(i.free_standing),
                                p.variable, p.a_max0, p.reference)
    io.write_netcdf(table, snakemake.output.nc)
    io.write_text(tables.table_csv(table), snakemake.output.csv)
    io.write_text(tables.table_markdown(table), snakemake.output.md)


if "snakemake" in globals():
    jobs.run(main, snakemake)
