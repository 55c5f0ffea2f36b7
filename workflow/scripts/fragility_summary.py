"""The fragility medians of every strategy on every record set, side by side (with intervals)."""
import pandas as pd

from rockstudy.analysis.fragility import suite_summary
from rockstudy.core import io
from rockstudy.report import suite_summary_markdown
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    rows = suite_summary(job.read_all(snakemake.input))
    io.write_text(pd.DataFrame(rows).to_csv(index=False, float_format="%.5g"), snakemake.output.csv)
    io.write_text(suite_summary_markdown(rows), snakemake.output.md)


if "snakemake" in globals():
    jobs.run(main, snakemake)
