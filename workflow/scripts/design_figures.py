"""Design charts: J_OS maps, which strategy wins where, the size effect, and the device sweep."""
from rockstudy import plotting
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    blocks = job.read(snakemake.input.blocks)
    devices = job.read(snakemake.input.devices)
    out = snakemake.output
    plotting.save_figure(plotting.figure_design_jos_maps(blocks, ("CS01", "CS02")), out.jos, out.jos_pdf)
    plotting.save_figure(plotting.figure_design_winner(blocks), out.winner, out.winner_pdf)
    plotting.save_figure(plotting.figure_design_size_effect(blocks), out.size, out.size_pdf)
    plotting.save_figure(plotting.figure_design_devices(devices, snakemake.params.target), out.devices,
                         out.devices_pdf)


if "snakemake" in globals():
    jobs.run(main, snakemake)
