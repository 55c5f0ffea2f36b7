"""Risk of overturning of every strategy of one record set at the config's scenarios and hazard curves."""
from rockstudy.analysis.hazard import read_hazard_sites
from rockstudy.analysis.risk_sites import risk_dataset, risk_warnings_markdown
from rockstudy.core import io
from rockstudy.report import risk_markdown
from rockstudy.studies import jobs


def main(snakemake):
    job = jobs.open_job(snakemake)
    p = snakemake.params
    curves = {name: read_hazard_sites(path, f"risk.hazard_curves.{name}", p.hazard_units.get(name))
              for name, path in p.hazard_curves.items()}
    ds = risk_dataset(job.read(snakemake.input.fragility), scenarios=p.scenarios, hazard_curves=curves,
                      years=p.years, gmm=p.gmm, outside_gmm_range=p.outside_gmm_range)
    io.write_netcdf(job.stamp(ds), snakemake.output.nc)
    per_site = [name for name, var in ds.data_vars.items() if var.dims[:1] == ("strategy",) and var.ndim <= 2]
    io.write_text(ds[per_site].to_dataframe().to_csv(float_format="%.5g"), snakemake.output.csv)
    io.write_text(risk_markdown(ds) + risk_warnings_markdown(ds), snakemake.output.md)


if "snakemake" in globals():
    jobs.run(main, snakemake)
