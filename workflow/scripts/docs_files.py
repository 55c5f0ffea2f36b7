"""The run's figures and numbers quoted by the README and docs/, copied into docs/figures/."""
import shutil

from rockstudy.core import io
from rockstudy.report import run_numbers_csv
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    for source, target in zip(snakemake.input.figures, snakemake.output.figures, strict=True):
        shutil.copyfile(source, target)
    io.write_text(run_numbers_csv(job.read_all(snakemake.input.fragility)), snakemake.output.numbers)


if "snakemake" in globals():
    jobs.run(main, snakemake)
