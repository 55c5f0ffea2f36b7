"""A Markdown table of the study as an HTML page for the report."""
from pathlib import Path

from rockstudy import report as report_pages
from rockstudy.core import io
from rockstudy.studies import jobs


def main(snakemake):
    jobs.open_job(snakemake)
    text = Path(snakemake.input[0]).read_text(encoding="utf-8")
    io.write_text(report_pages.markdown_page(text), snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
