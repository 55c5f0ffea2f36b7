"""Every HTML page of `all` for the report: tables, claims, Table 1 beside the paper, the overview's fragments."""
from pathlib import Path

from rockstudy import report as report_pages
from rockstudy.core import io
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    inp, out = snakemake.input, snakemake.output
    claims, comparison = job.read(inp.claims), job.read(inp.comparison)
    io.write_text(report_pages.document(str(claims.attrs.get("title", "Claims")), report_pages.claims_html(claims)),
                  out.claims)
    io.write_text(report_pages.document(str(comparison.attrs.get("title", "Table 1")),
                                        report_pages.table1_beside_paper_html(comparison)), out.comparison)
    io.write_text(report_pages.overview_html(comparison, claims), out.overview)
    io.write_text(report_pages.beyond_overview_html(job.read_all(inp.fragility), job.read_all(inp.risk)),
                  out.overview_beyond)
    for md, page in zip(inp.tables, out.tables, strict=True):
        io.write_text(report_pages.markdown_page(Path(md).read_text(encoding="utf-8")), page)


if "snakemake" in globals():
    jobs.run(main, snakemake)
