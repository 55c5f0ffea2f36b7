"""Risk of overturning of every strategy of one record set at the config's scenarios and hazard curves."""
from rockstudy.analysis.hazard import read_hazard_curve
from rockstudy.analysis.risk import risk_dataset
from rockstudy.core import io
from rockstudy.report import risk_markdown
from rockstudy.studies import study

study.log_to(snakemake.log[0])
p = snakemake.params
read_nc = io.reader(p.expect)
curves = {name: read_hazard_curve(path, f"risk.hazard_curves.{name}") for name, path in p.hazard_curves.items()}
ds = risk_dataset(read_nc(snakemake.input.fragility), scenarios=p.scenarios, hazard_curves=curves, years=p.years,
                  gmm=p.gmm)
ds.attrs["rockstudy_source_sha256"] = p.library
io.write_netcdf(ds, snakemake.output.nc)
per_site = [name for name, var in ds.data_vars.items() if var.dims[:1] == ("strategy",) and var.ndim <= 2]
io.write_text(ds[per_site].to_dataframe().to_csv(float_format="%.5g"), snakemake.output.csv)
io.write_text(risk_markdown(ds), snakemake.output.md)
