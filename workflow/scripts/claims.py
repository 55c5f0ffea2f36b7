"""The claims checklist of §5 and the Conclusions, and Table 1 side by side with the paper."""
from rockstudy import report
from rockstudy.core import io
from rockstudy.studies import claims, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
p, i = snakemake.params, snakemake.input
read = lambda paths: [read_nc(path) for path in paths]  # noqa: E731
table1 = read_nc(i.table1)
results = claims.evaluate_run(table1, read(i.spectra), dict(p.noise_levels), p.a_max0,
                              convergence=read_nc(i.convergence), sampling=read_nc(i.sampling),
                              delay=read_nc(i.delay))
comparison = claims.table1_comparison(table1)
header = (f"Noise reading: {report.settings_text(p.reading)}. Anchorage: {report.settings_text(p.anchorage)}. "
          f"Realisations: {p.realisations}.")
io.write_netcdf(claims.claims_dataset(results, {"noise_reading": p.reading, "anchorage": str(p.anchorage)}),
                snakemake.output.nc)
io.write_text(claims.claims_markdown(results, comparison, header), snakemake.output.md)
io.write_text(claims.claims_csv(results), snakemake.output.csv)
io.write_netcdf(comparison, snakemake.output.comparison_nc)
io.write_text(comparison.to_dataframe().reset_index().to_csv(index=False, float_format="%.2f"),
              snakemake.output.comparison_csv)
