"""One point of the device sweep: the fragility median of every strategy with one (kappa_max, xi)."""
from rockstudy.core import io
from rockstudy.model.record_suites import load_suite
from rockstudy.studies import design, jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake)
    p = snakemake.params
    d = p.design
    kappa_max = float(snakemake.wildcards.kappa)
    ds = design.device_point(parameters.block_from_dict(p.block), kappa_max, float(snakemake.wildcards.xi),
                             d["strategies"], [r for _, r in load_suite(d["suite"])],
                             design.pga_levels(**d["pga_levels_g"]), suite=d["suite"],
                             kappa_min=min(p.anchorage["kappa_min"], kappa_max),
                             overturn_criterion=p.overturn_criterion, free_time=p.free_time)
    io.write_netcdf(job.stamp(ds), snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
