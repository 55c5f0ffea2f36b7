"""P(overturn) at every (omega_p/p, a_p/(g tan alpha)) point over the noise realisations (Eq. P1)."""
from rockstudy.analysis.probability import probability_surface
from rockstudy.core import io
from rockstudy.studies import jobs, parameters


def main(snakemake):
    job = jobs.open_job(snakemake, compiled=True)
    p = snakemake.params
    scenario = parameters.scenario_from_dict(p.scenario)
    job.read(snakemake.input.noise)  # the level's noise file is the one this scenario's records come from
    ds = probability_surface(scenario,
                             parameters.frequency_ratios(p.frequency_grid, "beyond.probability.frequency_grid"),
                             realisations=range(p.realisations),
                             grid=parameters.amplitude_grid(p.amplitude_grid, "beyond.probability.amplitude_grid"))
    io.write_netcdf(job.stamp(ds), snakemake.output[0])


if "snakemake" in globals():
    jobs.run(main, snakemake)
