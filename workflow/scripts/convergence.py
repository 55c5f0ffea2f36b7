"""Fig. 6a data: a_min,OVER over the first N noise realisations, N = 1 ... n."""
from rockstudy.core import io
from rockstudy.studies import datasets, study

read_nc = io.reader(snakemake.params.expect)

study.log_to(snakemake.log[0])
ds = read_nc(snakemake.input[0])
if ds.sizes["realisation"] != snakemake.params.realisations:
    raise ValueError(f"spectrum has {ds.sizes['realisation']} realisations, expected {snakemake.params.realisations}")
io.write_netcdf(datasets.convergence_dataset(ds), snakemake.output[0])
