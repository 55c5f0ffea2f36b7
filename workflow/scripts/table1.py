"""Table 1: J_OS at each noise level against the noise-free strategy and against FS (Eqs. 18-22)."""
from rockstudy.core import io
from rockstudy.studies import jobs, tables


def main(snakemake):
    job = jobs.open_job(snakemake)
    p = snakemake.params
    table = tables.table1(job.read_all(snakemake.input), p.strategies, dict(p.noise_levels), p.a_max0)
    io.write_netcdf(table, snakemake.output.nc)
    io.write_text(tables.table_csv(table), snakemake.output.csv)
    io.write_text(tables.table_markdown(table), snakemake.output.md)


if "snakemake" in globals():
    jobs.run(main, snakemake)
