"""The block and device sweeps gathered from their points, and the device-design answer as Markdown."""
from rockstudy.core import io
from rockstudy.studies import design, jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    blocks = design.gather_blocks(job.read_all(snakemake.input.blocks))
    devices = design.gather_devices(job.read_all(snakemake.input.devices))
    io.write_netcdf(blocks, snakemake.output.blocks)
    io.write_netcdf(devices, snakemake.output.devices)
    spec = snakemake.params.block
    label = (f"block {spec['preset']}" if "preset" in spec
             else "block " + ", ".join(f"{k} = {v}" for k, v in spec.items()))
    io.write_text(design.design_markdown(devices, snakemake.params.target, label), snakemake.output.md)


if "snakemake" in globals():
    jobs.run(main, snakemake)
