"""Every HTML page of `all` for the report: tables, claims, Table 1 beside the paper, the overview's fragments."""
from pathlib import Path

from rockstudy import report as report_pages
from rockstudy.core import io

inp, out = snakemake.input, snakemake.output
claims, comparison = io.read_netcdf(inp.claims), io.read_netcdf(inp.comparison)
io.write_text(report_pages.document(str(claims.attrs.get("title", "Claims")), report_pages.claims_html(claims)),
              out.claims)
io.write_text(report_pages.document(str(comparison.attrs.get("title", "Table 1")),
                                    report_pages.table1_beside_paper_html(comparison)), out.comparison)
io.write_text(report_pages.overview_html(comparison, claims), out.overview)
io.write_text(report_pages.beyond_overview_html([io.read_netcdf(path) for path in inp.fragility]),
              out.overview_beyond)
for md, page in zip(inp.tables, out.tables, strict=True):
    io.write_text(report_pages.markdown_page(Path(md).read_text(encoding="utf-8")), page)
