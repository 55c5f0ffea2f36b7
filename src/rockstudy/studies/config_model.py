"""Every input of a study config declared once: type, unit, range and size limit.

The models below (pydantic v2, strict: a ``bool`` is not a number, NaN and inf are refused, an unknown key
is refused) are the one declaration of the study config. From them come

* the JSON schema Snakemake validates ``config.yaml`` against (``workflow/schemas/config.schema.yaml``,
  written by ``python -m rockstudy.studies.config_model``; a test fails when the checked-in file is stale),
* :func:`check_config`, the first step of :func:`rockstudy.studies.study.check_study` and of the CLI's
  ``--config``, whose error names the key path, the value, what is allowed and, for an unknown key, the
  closest known one,
* :func:`check_value`, the check of one value by its key path (``"anchorage.kappa_max"``).

The ranges of numeric keys are those of :mod:`rockstudy.core.quantities`, the other limits those of
:mod:`rockstudy.core.limits`. Relations between keys (a noise level named by
a sweep exists, a_max,0 within the scan, the work of one job) are checked after these declarations by
:func:`rockstudy.studies.study.check_study`. pydantic is imported only here and by
:mod:`rockstudy.studies.config_messages`, and only by the config checks: neither ``rockstudy --help`` nor a
simulation loads it. ``core`` holds no config model: the models live with the study that reads them.
"""
from __future__ import annotations

from typing import Annotated, Literal, Union

from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Field,
    JsonValue,
    StringConstraints,
    TypeAdapter,
    ValidationError,
    create_model,
    model_validator,
)

from rockstudy.core import risk_inputs as r
from rockstudy.core import validation as v
from rockstudy.core.config_files import count_nodes
from rockstudy.core.limits import EXCITATIONS, LEVEL_MEANINGS, MAX_TEXT, OVERTURN_CRITERIA, RESCALES, STRATEGIES
from rockstudy.core.quantities import MAX_PGA_G, MAX_ROTATION_RATIO, QUANTITIES
from rockstudy.core.validation import InputError
from rockstudy.studies import config_messages
from rockstudy.studies.config_messages import KeyRelationError, _model_at, _short

SCHEMA_PATH = "workflow/schemas/config.schema.yaml"
"""Where the generated schema is checked in, relative to the repository."""

# The names the library accepts: the library's own tuples (core.limits), and those of modules that load numba
# (a test keeps these equal to theirs)
BLOCK_PRESETS = ("BLC06",)
SUITES = ("p695-far-field", "p695-near-field-pulse", "p695-near-field-no-pulse", "synthetic")
RECORD_UNITS = ("g", "m/s^2", "m/s2", "cm/s^2", "cm/s2", "gal", "mm/s^2", "mm/s2")
INTENSITY_MEASURES = ("pga_ratio", "pgv_ratio")


def _unique(items: list) -> list:
    if len(set(map(repr, items))) != len(items):
        raise ValueError("the entries must be distinct")
    return items


def _list(item, low: int = 1, high: int = v.MAX_LIST_ITEMS, unique: bool = True):
    """A list of ``item``, ``low`` to ``high`` entries (distinct if ``unique``)."""
    extra: dict[str, JsonValue] | None = {"uniqueItems": True} if unique else None
    checks = [AfterValidator(_unique)] if unique else []
    field = Field(min_length=low, max_length=high, json_schema_extra=extra)
    return Annotated[(list[item], field, *checks)]


def _number(unit: str = "", **limits):
    """A number of a config-only range (one that no library argument shares)."""
    return Annotated[float, Field(description=f"[{unit}]" if unit else None, **limits)]


def Q(name: str):  # noqa: N802 -- reads as the type it returns
    """The declared type of the quantity ``name`` (:data:`rockstudy.core.quantities.QUANTITIES`).

    Parameters
    ----------
    name : str
        A key of :data:`~rockstudy.core.quantities.QUANTITIES` (``"kappa"``, ``"noise_level"`` ...).

    Returns
    -------
    type
        ``Annotated[float, Field(...)]`` (or ``int``; ``| None`` when optional), see
        :meth:`rockstudy.core.quantities.Quantity.annotated`.
    """
    return QUANTITIES[name].annotated()


Strategy = Literal[STRATEGIES]
Strategies = _list(Strategy)
LevelName = Annotated[str, StringConstraints(pattern=r"^[A-Za-z0-9]+$", max_length=64)]
Ratio = Q("frequency_ratio")
AmplitudeRatio = Q("amplitude_ratio")
Seconds = _number("s", gt=0, le=v.MAX_TIME_SPAN)
Rotation = Q("ultimate_rotation")
Kappa = Q("kappa")
Damping = Q("damping_ratio")
Count = Annotated[int, Field(ge=1, le=v.MAX_REALISATIONS)]
Seed = Q("seed")


class Section(BaseModel):
    """A config section: strict types, no unknown key, finite numbers."""
    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


class Block(Section):
    """A preset name, or the dimensions [m] (and density [kg/m^3], restitution [-])."""
    model_config = ConfigDict(json_schema_extra={"oneOf": [
        {"required": ["preset"], "not": {"anyOf": [{"required": [k]} for k in ("width", "height", "depth")]}},
        {"required": ["width", "height", "depth"], "not": {"required": ["preset"]}}]})
    preset: Literal[BLOCK_PRESETS] = None
    width: Q("length") = None
    height: Q("length") = None
    depth: Q("length") = None
    density: Q("density") = None
    restitution: Q("restitution") = None

    @model_validator(mode="after")
    def _one_way(self):
        dims = [k for k in ("width", "height", "depth") if getattr(self, k) is not None]
        if self.preset is not None and dims:
            raise ValueError(f"give either a preset or the dimensions, not both (got preset and {', '.join(dims)})")
        if self.preset is None and len(dims) < 3:
            raise ValueError("give a preset, or width, height and depth")
        return self


class Anchorage(Section):
    kappa_max: Kappa
    kappa_min: Kappa
    damping_ratio: Damping
    spring_ultimate_rotation: Rotation
    damper_ultimate_rotation: Rotation


class Reading(Section):
    """A noise reading (:class:`rockstudy.model.noise.NoiseReading`); a missing key takes the library's default."""
    step: Q("noise_step") = None
    rescale: Literal[RESCALES] = None
    level_means: Literal[LEVEL_MEANINGS] = None
    band: Q("band") = None
    span: Q("noise_span") = None


class Noise(Reading):
    """The study's noise reading: every key given."""
    step: Q("noise_step")
    rescale: Literal[RESCALES]
    level_means: Literal[LEVEL_MEANINGS]
    band: Q("band")
    span: Q("noise_span")


class Control(Section):
    sensor_band: Q("band")


class Grid(Section):
    start: Ratio
    stop: Ratio
    step: Ratio


class AmplitudeGrid(Section):
    start: AmplitudeRatio
    stop: AmplitudeRatio
    step: AmplitudeRatio
    resolution: Q("amplitude_resolution")


class Table1(Section):
    strategies: Strategies


class Convergence(Section):
    strategy: Strategy
    noise_level: LevelName


class SamplingSweep(Section):
    strategies: Strategies
    noise_level: LevelName
    sampling_times: _list(Seconds)


class DelaySweep(Section):
    strategies: Strategies
    noise_level: LevelName
    sampling_time: Seconds
    delays: _list(Seconds)


class ControlHistories(Section):
    strategies: Strategies
    frequency_ratio: Ratio
    amplitude_ratio: AmplitudeRatio


class ExamplePoint(Section):
    label: Annotated[str, StringConstraints(pattern=r"^[A-Za-z0-9_-]+$", max_length=64)]
    strategy: Strategy
    noise_level: LevelName
    realisations: _list(Annotated[int, Field(ge=0, le=v.MAX_REALISATIONS - 1)], high=4)
    frequency_ratio: Ratio
    amplitude_ratio: AmplitudeRatio


class Maps(Section):
    strategies: Strategies


ReadingName = Annotated[str, StringConstraints(pattern=r"^[A-Za-z0-9_]+$", max_length=64)]


class Reproduction(Section):
    strategy: Strategy
    realisations: Count
    readings: Annotated[dict[ReadingName, Reading], Field(min_length=1, max_length=v.MAX_LIST_ITEMS)]


class Calibration(Section):
    kappa_max: _list(Kappa)
    damping_ratio: _list(Damping)
    ultimate_rotation_ratio: _list(_number("-", gt=0, le=MAX_ROTATION_RATIO))
    kappa_min_ratio: _list(_number("-", ge=0, le=1))
    coarse_realisations: Count
    coarse_frequency_grid: Grid
    candidates: Annotated[int, Field(ge=1, le=v.MAX_DEVICES)]


class Probability(Section):
    strategies: Strategies
    noise_levels: _list(LevelName)
    frequency_grid: Grid
    amplitude_grid: AmplitudeGrid


class RecordFile(Section):
    path: Annotated[str, StringConstraints(min_length=1, max_length=MAX_TEXT)]
    unit: Literal[RECORD_UNITS] = None


RecordName = Annotated[str, StringConstraints(pattern=r"^[A-Za-z0-9_-]+(:[^/\\:]+)?$", max_length=256)]


class Synthetic(Section):
    n_records: Q("suite_records")
    seed: Seed
    ground_frequency_hz: _list(Q("ground_frequency_hz"), low=2, high=2, unique=False)
    ground_damping: _list(Q("ground_damping"), low=2, high=2, unique=False)
    peak_time: _list(Seconds, low=2, high=2, unique=False)
    envelope_shape: Q("envelope_shape")
    filter_ratio: Q("filter_ratio")
    duration: Seconds
    dt: Seconds
    pga_g: Q("pga_g")


class Fragility(Section):
    strategies: Strategies
    records: Union[Literal[SUITES], _list(Union[RecordName, RecordFile], high=v.MAX_SUITE_RECORDS, unique=False)]
    synthetic: Synthetic
    intensity_measure: Literal[INTENSITY_MEASURES]
    intensity_levels: Grid
    threshold_resolution: Q("intensity_resolution")
    bootstrap: Q("bootstrap")
    seed: Seed


class Beyond(Section):
    """Beyond the paper (optional): P(overturn) over noise realisations and record fragility."""
    probability: Probability
    fragility: Fragility


class PgaLevels(Section):
    start: Q("design_pga_g")
    stop: Q("design_pga_g")
    count: Q("stripe_count")


class DesignAmplitudeGrid(Section):
    start: AmplitudeRatio
    step: Q("design_step")
    resolution: Q("design_resolution")


class DesignBlocks(Section):
    R: _list(Q("half_diagonal"))
    alpha: _list(Q("slenderness"))
    frequency_grid: Grid
    amplitude_grid: DesignAmplitudeGrid
    a_max0: Q("a_max0_g")


class DesignDevices(Section):
    kappa_max: _list(Kappa)
    damping_ratio: _list(Damping)
    target_median_g: _number("g", gt=0, le=MAX_PGA_G)


class Design(Section):
    """Design charts (optional): block sweep over (R, alpha) and device sweep over (kappa_max, xi)."""
    suite: Literal[SUITES]
    strategies: Strategies
    pga_levels_g: PgaLevels
    blocks: DesignBlocks
    devices: DesignDevices


def _scenario(name: str):
    return r.SCENARIO_INPUTS[name].annotated()


def _risk(name: str):
    return r.RISK_INPUTS[name].annotated()


class Scenario(Section):
    """An earthquake scenario of a ground-motion model (:data:`rockstudy.core.risk_inputs.SCENARIO_INPUTS`)."""
    mag: _scenario("mag")
    dist_rup: _scenario("dist_rup")
    v_s30: _scenario("v_s30")
    dist_jb: _scenario("dist_jb") = None
    dist_x: _scenario("dist_x") = None
    dip: _scenario("dip") = None
    depth_tor: _scenario("depth_tor") = None
    mechanism: Literal[r.MECHANISMS] = None


RiskName = Annotated[str, StringConstraints(pattern=r"^[A-Za-z0-9_-]+$", max_length=64)]


class Risk(Section):
    """Risk at a site (optional): the rate and probability of overturning per record set and strategy, from
    hazard curves (files: PGA [g], annual rate of exceedance [1/yr]) and earthquake scenarios."""
    years: _risk("years") = None
    gmm: Literal[tuple(r.GMMS)] = None
    scenarios: Annotated[dict[RiskName, Scenario], Field(max_length=r.MAX_SCENARIOS)] = None
    hazard_curves: Annotated[dict[RiskName, Annotated[str, StringConstraints(min_length=1, max_length=MAX_TEXT)]],
                             Field(max_length=r.MAX_SCENARIOS)] = None
    hazard_units: Annotated[dict[RiskName, Literal[tuple(r.HAZARD_UNITS)]], Field(max_length=r.MAX_SCENARIOS)] = None
    outside_gmm_range: bool = None


class Study(Section):
    """The study of the paper (§5). Every key is required except ``beyond``, ``design`` and ``risk``; no other keys are
    allowed. Relations between keys are checked by rockstudy.studies.study.check_study."""
    # (the relations that need no computation are this model's validators, which check_study runs first; the
    # class docstring is the schema's description)
    results_dir: Annotated[str, StringConstraints(min_length=1, max_length=MAX_TEXT)]
    block: Block
    anchorage: Anchorage
    strategies: Strategies
    excitation: Literal[EXCITATIONS]
    overturn_criterion: Literal[OVERTURN_CRITERIA]
    free_time: Q("free_time")
    noise_levels: Annotated[dict[LevelName, Q("noise_level")],
                            Field(min_length=1, max_length=v.MAX_LIST_ITEMS)]
    realisations: Count
    realisations_per_job: Count
    seed: Seed
    noise: Noise
    control: Control
    noise_reference_frequency_ratio: Ratio
    noise_records_stored: Count
    frequency_grid: Grid
    amplitude_grid: AmplitudeGrid
    a_max0: Q("a_max0_g")
    table1: Table1
    convergence: Convergence
    sampling_sweep: SamplingSweep
    delay_sweep: DelaySweep
    control_histories: ControlHistories
    example_point: ExamplePoint
    maps: Maps
    reproduction: Reproduction
    calibration: Calibration
    beyond: Beyond = None
    design: Design = None
    risk: Risk = None

    @model_validator(mode="after")
    def _names_exist(self):
        """The noise level each sweep names is one of ``noise_levels``; the strategies of each table and sweep
        are studied, FS among them; the example's realisations are among the study's."""
        levels = self.noise_levels
        for key in ("convergence", "sampling_sweep", "delay_sweep", "example_point"):
            name = getattr(self, key).noise_level
            if name not in levels:
                raise KeyRelationError(f"{key}.noise_level: {name!r} is not one of noise_levels ({', '.join(levels)})")
        for key in ("table1", "maps", "control_histories", "sampling_sweep", "delay_sweep"):
            missing = set(getattr(self, key).strategies) - set(self.strategies)
            if missing:
                raise KeyRelationError(f"{key}.strategies: {sorted(missing)} not in strategies {list(self.strategies)}")
        if "FS" not in self.strategies:
            raise KeyRelationError("strategies: FS is needed as the reference of Table 1 and of the timing tables")
        too_high = [k for k in self.example_point.realisations if k >= self.realisations]
        if too_high:
            raise KeyRelationError(f"example_point.realisations: {too_high} >= realisations ({self.realisations})")
        return self


def _declared(info):
    """The declared type of a model field, with its constraints."""
    return Annotated[(info.annotation, *info.metadata)] if info.metadata else info.annotation


PartialStudy = create_model(
    "PartialStudy", __base__=Section, __doc__="A study config in which any top-level key may be left out (the CLI's "
    "--config): what is given is checked as declared in Study.",
    **{name: (_declared(info), None) for name, info in Study.model_fields.items()})

_MODEL_NAMES = {cls.__name__ for cls in (*Section.__subclasses__(), Noise)}
"""The sections' class names, which pydantic puts into the location of an error inside a union."""

OPTIONS = {
    "--realisations": Count, "--record-scale": Q("record_scale"),
}
"""The command line's numeric options that reach no library check naming them before any work (the number of
realisations, a record's scale before the record is read), each declared like the config key it
stands for; the CLI checks them with :func:`check_option`. Every other option is checked by the object,
function or method it is passed to, which names the option (``Anchorage(..., names=...)``,
``Scenario.motion(..., names=...)``, ``read_record(..., names=...)``)."""

# ----------------------------------------------------------------------------------------------- checks

def message(error: ValidationError, model=None, prefix: str = "") -> str:
    """At most three lines for the first error of ``error`` (:func:`rockstudy.studies.config_messages.message`,
    with the sections' class names left out of the key path).

    Parameters
    ----------
    error : pydantic.ValidationError
        The error pydantic raised for a config.
    model : type of pydantic.BaseModel, optional
        The model the config was checked against (it lists the known keys next to an unknown one).
    prefix : str, optional
        Text put before the key path (``"config.yaml: "``).
    """
    return config_messages.message(error, model, prefix, _MODEL_NAMES)


def check_config(config, model=Study, name: str = "") -> None:
    """Refuse a config (a parsed ``config.yaml``) that its declaration does not allow, naming the key path
    (after ``name``, e.g. the file) in at most three lines (:class:`InputError`). The config is not changed.

    Parameters
    ----------
    config : dict
        The parsed config; its size is checked first (:func:`rockstudy.core.config_files.count_nodes`).
    model : type of pydantic.BaseModel, optional
        Its declaration: :class:`Study` (default), :data:`PartialStudy` for the CLI's ``--config``, or a
        section such as :class:`Risk`.
    name : str, optional
        What messages call the config (a file name); "" names the key path alone.

    Raises
    ------
    rockstudy.core.validation.InputError
        For the first key its declaration does not allow (or a config too large).
    """
    count_nodes(config, name=name or "config")
    try:
        model.model_validate(config)
    except ValidationError as exc:
        raise InputError(message(exc, model, f"{name}: " if name else "")) from None


def field_type(path: str, model=Study):
    """The declared type of the config key ``path`` (``"anchorage.kappa_max"``), with its constraints.

    Parameters
    ----------
    path : str
        The key path, sections joined by dots.
    model : type of pydantic.BaseModel, optional
        The model the path starts in (default :class:`Study`).

    Raises
    ------
    KeyError
        If ``path`` is not a declared key.
    """
    parts = path.split(".")
    section = _model_at(model, parts[:-1]) if len(parts) > 1 else model
    if section is None or parts[-1] not in section.model_fields:
        raise KeyError(f"{path} is not a declared config key")
    return _declared(section.model_fields[parts[-1]])


_ADAPTERS: dict = {}


def check_value(path: str, value, name: str | None = None):
    """``value`` against the declaration of the config key ``path``. Returns the value.

    Parameters
    ----------
    path : str
        The config key whose declaration applies (e.g. ``"anchorage.kappa_max"``, see :func:`field_type`).
    value : object
        The value to check.
    name : str, optional
        The input's name in the message (e.g. the option ``--kappa-max``); None: the key path.

    Raises
    ------
    rockstudy.core.validation.InputError
        If the declaration does not allow ``value``.
    """
    if path not in _ADAPTERS:
        declared = field_type(path)
        model = isinstance(declared, type) and issubclass(declared, BaseModel)
        _ADAPTERS[path] = TypeAdapter(declared, config=None if model else ConfigDict(strict=True, allow_inf_nan=False))
    try:
        return _ADAPTERS[path].validate_python(value)
    except ValidationError as exc:
        err = exc.errors(include_url=False)[0]
        raise InputError(f"{name or path} = {_short(value)} is not allowed: {err['msg']}") from None


def check_option(name: str, value):
    """A command-line option's value against :data:`OPTIONS`. Returns the value.

    Parameters
    ----------
    name : str
        The option, a key of :data:`OPTIONS` (``"--kappa-max"``); the message names it.
    value : object
        The option's value; None (not given) is allowed and returned.

    Raises
    ------
    rockstudy.core.validation.InputError
        If the option's declaration does not allow ``value``.
    """
    if value is None:
        return None
    if name not in _ADAPTERS:
        _ADAPTERS[name] = TypeAdapter(OPTIONS[name], config=ConfigDict(strict=True, allow_inf_nan=False))
    try:
        return _ADAPTERS[name].validate_python(value)
    except ValidationError as exc:
        err = exc.errors(include_url=False)[0]
        raise InputError(f"{name} = {_short(value)} is not allowed: {err['msg']}") from None


# ----------------------------------------------------------------------------------------------- schema

def _tidy(node):
    """The generated schema without pydantic's titles and defaults (Snakemake's validate would write the
    defaults into the config), dict keys constrained by ``propertyNames``."""
    if isinstance(node, dict):
        node = {k: _tidy(item) for k, item in node.items() if k not in ("title", "default")}
        pattern = node.pop("patternProperties", None)
        if pattern:
            (key, value), = pattern.items()
            node["propertyNames"] = {"pattern": key}
            node["additionalProperties"] = value
        return node
    if isinstance(node, list):
        return [_tidy(item) for item in node]
    return node


def config_schema() -> dict:
    """The JSON schema (draft 2020-12) of the study config, generated from :class:`Study`."""
    schema = _tidy(Study.model_json_schema())
    return {"$schema": "https://json-schema.org/draft/2020-12/schema", **schema}


def schema_text() -> str:
    """The checked-in schema file's text: a generated-file header and :func:`config_schema` as YAML."""
    import yaml
    header = ("# GENERATED from rockstudy.studies.config_model (python -m rockstudy.studies.config_model); "
              "do not edit.\n"
              "# Snakemake validates config.yaml against it; rockstudy.studies.study.check_study checks the rest.\n")
    return header + yaml.safe_dump(config_schema(), sort_keys=False, width=118)


if __name__ == "__main__":  # pragma: no cover
    import sys
    from pathlib import Path
    target = Path(sys.argv[1] if len(sys.argv) > 1 else SCHEMA_PATH)
    target.write_text(schema_text())
    print(f"wrote {target}")
