"""The fragility medians of every strategy on every record set, side by side (with intervals)."""
import pandas as pd

from rockstudy.analysis.fragility import suite_summary
from rockstudy.core import io
from rockstudy.report import suite_summary_markdown
from rockstudy.studies import study

study.log_to(snakemake.log[0])
rows = suite_summary([io.read_netcdf(path) for path in snakemake.input])
io.write_text(pd.DataFrame(rows).to_csv(index=False, float_format="%.5g"), snakemake.output.csv)
io.write_text(suite_summary_markdown(rows), snakemake.output.md)
