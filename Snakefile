# rockstudy: reproduce every study, figure and table of "Use of overturning spectra in the
# performance evaluation of on-off control strategies for rocking objects" (§4-5).
#
#   snakemake -j2                                   # the paper's study (config.yaml)
#   snakemake -j2 --configfile .test/config.yaml --replace-workflow-config   # tiny study
#   snakemake --report report.html                  # the study as one HTML page: overview, tables, figures
#   snakemake -j2 probability | fragility           # beyond the paper (config `beyond:`; fragility is in `all`)
#
# DAG: noise -> spectrum_{,sampling,delay} -> convergence, tables, figures (with realisations_per_job <
#      realisations: noise -> spectrum_chunk -> gather_{spectrum,sampling,delay} -> ...); overturning_map
#      and time_history feed their figures directly.
import sys
from pathlib import Path

from snakemake.settings.types import DeploymentMethod
from snakemake.utils import min_version, validate

min_version("9.0")

try:  # the config is read and checked by the library itself, in the Python that runs snakemake
    from rockstudy.core import config_files
    from rockstudy.studies import device_calibration as calibration
    from rockstudy import report as report_pages
    from rockstudy.studies import parameters, study
except ImportError as exc:
    sys.exit(f"setup error: the Snakefile reads the config with the rockstudy package, which this Python "
             f"({sys.executable}) cannot import ({exc});\ninstall it beside snakemake, also for --sdm conda: "
             "python -m pip install -c constraints.txt -e .")

if DeploymentMethod.CONDA in workflow.deployment_settings.deployment_method:
    # workflow/envs/rockstudy.yaml installs rockstudy by pip from "../..", which conda resolves from Snakemake's
    # copy of the file in the conda prefix: that must be <this checkout>/.snakemake/conda
    _prefix = Path(workflow.deployment_settings.conda_prefix or Path(".snakemake", "conda")).resolve()
    if _prefix.parent.parent != Path(workflow.basedir).resolve():
        sys.exit(f"setup error: --sdm conda builds workflow/envs/rockstudy.yaml from its copy in {_prefix}, where "
                 f"its '-e ../..' is {_prefix.parent.parent}, not this checkout;\nrun snakemake in "
                 f"{workflow.basedir} without --conda-prefix or --directory")

try:  # the --configfile files as written (bounded, aliases expanded) and the --config KEY=VALUE words, typed as
    # in a file: each is an overlay that replaces the sections it gives, applied in Snakemake's order. A number
    # YAML 1.1 does not read as written (010: 8 in a file, 10 in Snakemake's --config) is refused on both.
    OVERLAYS = [config_files.load_yaml(path) for path in workflow.overwrite_configfiles]
    COMMAND_LINE = config_files.command_line_overlay(workflow.config_settings.config,
                                                     workflow.config_settings.config_args)
except ValueError as exc:
    sys.exit(f"config error: {exc}")


configfile: "config.yaml"


report: "workflow/report/workflow.rst"


# The config, checked against its declaration (rockstudy.studies.config_model) before anything walks it: an
# overlay (--configfile, then --config) replaces the sections it gives (a block by its dimensions replaces the
# preset), and a bad key ends the run with one short message naming it (exit 1, no traceback).
try:
    for overlay in OVERLAYS:
        config_files.replace_sections(config, overlay)
    config_files.apply_command_line(config, COMMAND_LINE)  # last, as Snakemake applies --config
    study.check_study(config)
except ValueError as exc:
    sys.exit(f"config error: {exc}")
validate(config, "workflow/schemas/config.schema.yaml")  # the schema generated from the same declaration


include: "workflow/rules/common.smk"
include: "workflow/rules/spectra.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/reproduction.smk"
include: "workflow/rules/beyond.smk"
include: "workflow/rules/risk.smk"
include: "workflow/rules/report.smk"
include: "workflow/rules/design.smk"
include: "workflow/rules/docs.smk"


localrules:
    all,
    convergence,
    table1,
    timing_table_sampling,
    timing_table_delay,
    figure_history,
    figure_excitation,
    figure_realisations,
    figure_noise_sensitivity,
    figure_sampling,
    figure_delay,
    figure_maps,
    claims,
    readings_table,
    figure_readings,
    calibration_grid,
    calibration_refine,


rule all:
    input:
        FIGURES,
        TABLES,
        CLAIMS,
        BEYOND_IN_ALL,
        REPORT_PAGES,
    default_target: True
