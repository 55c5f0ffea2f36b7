"""A Markdown table of the study as an HTML page for the report."""
from pathlib import Path

from rockstudy import report as report_pages
from rockstudy.core import io

io.write_text(report_pages.markdown_page(Path(snakemake.input[0]).read_text(encoding="utf-8")), snakemake.output[0])
