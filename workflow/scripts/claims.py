"""The claims checklist of §5 and the Conclusions, and Table 1 side by side with the paper."""
from rockstudy import report
from rockstudy.core import io
from rockstudy.studies import claims, jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    p, i = snakemake.params, snakemake.input
    table1 = job.read(i.table1)
    results = claims.evaluate_run(table1, job.read_all(i.spectra), dict(p.noise_levels), p.a_max0,
                                  convergence=job.read(i.convergence), sampling=job.read(i.sampling),
                                  delay=job.read(i.delay))
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


if "snakemake" in globals():
    jobs.run(main, snakemake)
