"""The block and device sweeps gathered from their points, and the device-design answer as Markdown."""
from rockstudy.core import io
from rockstudy.studies import design, study

study.log_to(snakemake.log[0])
blocks = design.gather_blocks(io.read_netcdf(path) for path in snakemake.input.blocks)
devices = design.gather_devices(io.read_netcdf(path) for path in snakemake.input.devices)
io.write_netcdf(blocks, snakemake.output.blocks)
io.write_netcdf(devices, snakemake.output.devices)
spec = snakemake.params.block
label = f"block {spec['preset']}" if "preset" in spec else "block " + ", ".join(f"{k} = {v}" for k, v in spec.items())
io.write_text(design.design_markdown(devices, snakemake.params.target, label), snakemake.output.md)
