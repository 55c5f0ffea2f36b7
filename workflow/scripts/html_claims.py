"""The claims checklist and Table 1 beside the paper as HTML pages, and the overview page's headline fragment."""
from rockstudy import report as report_pages
from rockstudy.core import io
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    claims, comparison = job.read(snakemake.input.claims), job.read(snakemake.input.comparison)
    io.write_text(report_pages.document(str(claims.attrs.get("title", "Claims")), report_pages.claims_html(claims)),
                  snakemake.output.claims)
    io.write_text(report_pages.document(str(comparison.attrs.get("title", "Table 1")),
                                        report_pages.table1_beside_paper_html(comparison)),
                  snakemake.output.comparison)
    io.write_text(report_pages.overview_html(comparison, claims), snakemake.output.overview)


if "snakemake" in globals():
    main(snakemake)
