"""One point of the block sweep: spectra, J_OS over FS and fragility medians of every strategy."""
from rockstudy.analysis.spectra import frequency_grid
from rockstudy.core import io
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.record_suites import load_suite
from rockstudy.studies import design, jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    p = snakemake.params
    d = p.design
    grid = d["blocks"]["amplitude_grid"]
    ds = design.block_point(float(snakemake.wildcards.R), float(snakemake.wildcards.alpha),
                            Anchorage(**p.anchorage), d["strategies"],
                            frequency_grid(**d["blocks"]["frequency_grid"]), amplitude_start=grid["start"],
                            amplitude_step=grid["step"], resolution=grid["resolution"],
                            a_max0_g=d["blocks"]["a_max0"], records=[r for _, r in load_suite(d["suite"])],
                            levels_g=design.pga_levels(**d["pga_levels_g"]), suite=d["suite"],
                            excitation=p.excitation, overturn_criterion=p.overturn_criterion, free_time=p.free_time)
    io.write_netcdf(job.stamp(ds), snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
