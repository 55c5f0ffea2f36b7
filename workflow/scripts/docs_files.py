"""The run's figures and numbers quoted by the README and docs/, copied into docs/figures/."""
import shutil

from rockstudy.core import io
from rockstudy.report import run_numbers_csv

for source, target in zip(snakemake.input.figures, snakemake.output.figures, strict=True):
    shutil.copyfile(source, target)
io.write_text(run_numbers_csv([io.read_netcdf(path) for path in snakemake.input.fragility]),
              snakemake.output.numbers)
