"""J_OS of the sampling (or delay) sweep against the same strategy without it and against FS (§5.2)."""
from rockstudy.core import io
from rockstudy.studies import study, tables

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
p = snakemake.params
read = lambda paths: [read_nc(path) for path in paths]  # noqa: E731
table = tables.timing_table(read(snakemake.input.sweep), read(snakemake.input.same_strategy),
                           read(snakemake.input.free_standing), p.variable, p.a_max0, p.reference)
io.write_netcdf(table, snakemake.output.nc)
io.write_text(tables.table_csv(table), snakemake.output.csv)
io.write_text(tables.table_markdown(table), snakemake.output.md)
