"""What every dataset of a study must say about itself, derived from the study config and a job's
wildcards (a strategy, a noise level, a sampling time, a record set, a design point), never from a
file's name.

A workflow step reads each input through :func:`rockstudy.studies.jobs.open_job`'s reader, which
compares the file with its expectation (:func:`rockstudy.core.io.check_dataset`: attributes, scalar
coordinates and coordinates) and with the dataset's own invariants
(:func:`rockstudy.studies.datasets.check_invariants`). A stale, swapped or edited file stops the step
with a message naming the file and what differs, instead of becoming a right-looking result.

:class:`StudyExpectations` takes the study config as plain ``dict`` values (as Snakemake loads it);
each method takes the wildcards of one dataset and returns its expected attributes as plain
JSON-able values.
"""
from __future__ import annotations

from functools import cached_property

from rockstudy.studies import parameters
from rockstudy.studies.datasets import expected_attrs


def scenario_spec(config: dict, strategy: str, level: str, sampling_time=0.0, delay=0.0) -> dict:
    """The scenario (as :func:`rockstudy.studies.parameters.scenario_from_dict` reads it) of a job of the
    study: ``strategy`` under the noise level named ``level``, with a sampling time and a delay.

    Parameters
    ----------
    config : dict
        The study config.
    strategy : str
        The control strategy (``"FS"``, ``"CS01"``, ...).
    level : str
        Name of the noise level, a key of ``noise_levels``.
    sampling_time : float, default 0.0
        Sampling time T_s of the controller; 0: continuous control. [s]
    delay : float, default 0.0
        Actuation delay of the controller. [s]
    """
    return {
        "block": config["block"],
        "anchorage": config["anchorage"],
        "control": {"strategy": strategy, "sampling_time": float(sampling_time), "delay": float(delay),
                    **config["control"]},
        "excitation": config["excitation"],
        "noise_level": config["noise_levels"][level],
        "seed": config["seed"],
        "noise": config["noise"],
        "overturn_criterion": config["overturn_criterion"],
        "free_time": config["free_time"],
    }


def reading_scenario_spec(config: dict, strategy: str, reading: str, level: str) -> dict:
    """The scenario of the readings study's spectrum of ``strategy`` under the noise reading ``reading``
    at ``level`` (a reading's missing keys take the library's defaults).

    Parameters
    ----------
    config : dict
        The study config.
    strategy : str
        The control strategy.
    reading : str
        Name of the noise reading, a key of ``reproduction.readings``.
    level : str
        Name of the noise level, a key of ``noise_levels``.
    """
    spec = scenario_spec(config, strategy, level)
    spec["noise"] = dict(config["reproduction"]["readings"][reading])
    return spec


def record_set_members(members) -> str:
    """The ``record_set_members`` attribute of a record set: its config entry (a suite name, or the list
    of ``SUITE:ID`` names and files) as text.

    Parameters
    ----------
    members : str or list
        The set's config entry: a suite name, or the list of ``SUITE:ID`` names and ``{path, unit}`` files
        (:func:`rockstudy.studies.beyond.record_sets`).
    """
    return members if isinstance(members, str) else repr(list(members))


class StudyExpectations:
    """The expected attributes of every dataset a study's jobs read, one method per kind of dataset.

    Parameters
    ----------
    config : dict
        The study config (``config.yaml``), already checked.
    """

    def __init__(self, config: dict):
        self.config = config
        self.levels = config["noise_levels"]
        self.free = parameters.noise_free_level(self.levels)

    # --- the study's grids and realisations ---------------------------------------------------------
    @cached_property
    def frequency_ratios(self) -> list:
        return [float(f) for f in parameters.frequency_ratios(self.config["frequency_grid"])]

    def chunks(self, level: str) -> list[list[int]]:
        """The realisation chunks of a level's spectra (one chunk of realisation 0 without noise).

        Parameters
        ----------
        level : str
            Name of the noise level, a key of ``noise_levels``.
        """
        return parameters.realisation_chunks(self.config["realisations"], self.config["realisations_per_job"],
                                             self.levels[level] > 0)

    def realisations(self, level: str) -> list[int]:
        """Every realisation of a level's spectra.

        Parameters
        ----------
        level : str
            Name of the noise level, a key of ``noise_levels``.
        """
        return [k for chunk in self.chunks(level) for k in chunk]

    def scenario(self, strategy: str, level: str, sampling_time=0.0, delay=0.0):
        """The :class:`~rockstudy.analysis.scenario.Scenario` of a job of the study (:func:`scenario_spec`).

        Parameters
        ----------
        strategy : str
            The control strategy.
        level : str
            Name of the noise level, a key of ``noise_levels``.
        sampling_time : float or str, default 0.0
            Sampling time T_s of the controller (a wildcard's text is converted); 0: continuous control. [s]
        delay : float or str, default 0.0
            Actuation delay of the controller. [s]
        """
        return parameters.scenario_from_dict(scenario_spec(self.config, strategy, level, sampling_time, delay))

    def _grids(self) -> dict:
        return {"frequency_ratios": self.frequency_ratios, "amplitude_grid": self.config["amplitude_grid"]}

    # --- the paper's study ----------------------------------------------------------------------------
    def noise(self, level: str) -> dict:
        """The noise realisations of ``level`` (rule noise).

        Parameters
        ----------
        level : str
            Name of the noise level, a key of ``noise_levels``.
        """
        return expected_attrs(self.scenario("FS", level), "noise", realisations=self.realisations(level))

    def spectrum(self, strategy: str, level: str, sampling_time=0.0, delay=0.0) -> dict:
        """A whole spectrum (its convergence too): every realisation of ``level``.

        Parameters
        ----------
        strategy : str
            The control strategy.
        level : str
            Name of the noise level, a key of ``noise_levels``.
        sampling_time : float or str, default 0.0
            Sampling time T_s of the controller; 0: continuous control. [s]
        delay : float or str, default 0.0
            Actuation delay of the controller. [s]
        """
        return expected_attrs(self.scenario(strategy, level, sampling_time, delay),
                              realisations=self.realisations(level), **self._grids())

    def chunk(self, strategy: str, level: str, sampling_time, delay, chunk) -> dict:
        """One realisation chunk of a spectrum (rule spectrum_chunk).

        Parameters
        ----------
        strategy : str
            The control strategy.
        level : str
            Name of the noise level, a key of ``noise_levels``.
        sampling_time : float or str
            Sampling time T_s of the controller; 0: continuous control. [s]
        delay : float or str
            Actuation delay of the controller. [s]
        chunk : int or str
            Index of the chunk among :meth:`chunks` of ``level``.
        """
        return expected_attrs(self.scenario(strategy, level, sampling_time, delay),
                              realisations=self.chunks(level)[int(chunk)], **self._grids())

    def map(self, strategy: str) -> dict:
        """The noise-free overturning map of ``strategy``.

        Parameters
        ----------
        strategy : str
            The control strategy.
        """
        return expected_attrs(self.scenario(strategy, self.free), "map", **self._grids())

    def history(self, strategy: str, level: str, realisation, frequency_ratio, amplitude_ratio) -> dict:
        """The time history of one case.

        Parameters
        ----------
        strategy : str
            The control strategy.
        level : str
            Name of the noise level, a key of ``noise_levels``.
        realisation : int or str
            The noise realisation k.
        frequency_ratio : float or str
            The case's ω_p/p. [-]
        amplitude_ratio : float or str
            The case's a_p/(g·tanα). [-]
        """
        return expected_attrs(self.scenario(strategy, level), "history", noise_realisation=int(realisation),
                              frequency_ratio=float(frequency_ratio), amplitude_ratio=float(amplitude_ratio))

    def table(self) -> dict:
        """A table of the study (Table 1, the timing tables, the readings table, the calibration's files):
        what it inherits from the study (block, excitation, seed, criterion, free time)."""
        return expected_attrs(self.scenario("FS", self.free), "study")

    def table1(self) -> dict:
        """Table 1 (``tables/table1.nc``): the study's attributes and ``table1.strategies``."""
        return {**self.table(), "strategy": list(self.config["table1"]["strategies"])}

    def timing_table(self, sweep: str) -> dict:
        """The J_OS table of the ``"sampling"`` or ``"delay"`` sweep: its strategies and sampling times (delays).

        Parameters
        ----------
        sweep : {"sampling", "delay"}
            The sweep: ``sampling_sweep`` or ``delay_sweep`` of the config.
        """
        if sweep == "sampling":
            spec = self.config["sampling_sweep"]
            return {**self.table(), "strategy": list(spec["strategies"]),
                    "sampling_time": [float(t) for t in spec["sampling_times"]]}
        if sweep == "delay":
            spec = self.config["delay_sweep"]
            return {**self.table(), "strategy": list(spec["strategies"]), "delay": [float(d) for d in spec["delays"]]}
        raise ValueError(f"sweep must be sampling or delay, got {sweep!r}")

    def claims(self) -> dict:
        """The claims checklist: made under the study's noise reading and anchorage."""
        return {"noise_reading": self.config["noise"], "anchorage": str(self.config["anchorage"])}

    def table1_comparison(self) -> dict:
        """Table 1 beside the paper (the paper's rows and noise levels: nothing of the study's settings)."""
        from rockstudy.studies.claims import COMPARISON_TITLE

        return {"title": COMPARISON_TITLE}

    # --- the readings study ---------------------------------------------------------------------------
    def reading_spectrum(self, strategy: str, reading: str, level: str) -> dict:
        """The spectrum of ``strategy`` under the noise reading ``reading`` at ``level`` (a reading's missing
        keys take the library's defaults).

        Parameters
        ----------
        strategy : str
            The control strategy.
        reading : str
            Name of the noise reading, a key of ``reproduction.readings``.
        level : str
            Name of the noise level, a key of ``noise_levels``.
        """
        spec = reading_scenario_spec(self.config, strategy, reading, level)
        realisations = list(range(self.config["reproduction"]["realisations"])) if self.levels[level] > 0 else [0]
        return expected_attrs(parameters.scenario_from_dict(spec), realisations=realisations, **self._grids())

    def readings_table(self) -> dict:
        """The readings study's table: one row per reading of ``reproduction.readings``."""
        return {"reading": list(self.config["reproduction"]["readings"]), "a_max0_g": float(self.config["a_max0"])}

    # --- the device calibration -----------------------------------------------------------------------
    @cached_property
    def calibration_devices(self) -> list[dict]:
        """The anchorages the calibration screens, in the order of its ``device`` wildcard."""
        from rockstudy.studies.device_calibration import CalibrationDesign

        cal = self.config["calibration"]
        design = CalibrationDesign(**{key: cal[key] for key in ("kappa_max", "damping_ratio",
                                                                 "ultimate_rotation_ratio", "kappa_min_ratio")})
        return design.devices(parameters.block_from_dict(self.config["block"]).alpha)

    def calibration_fs(self, level: str) -> dict:
        """The FS spectrum of ``level`` on the calibration's coarse grid.

        Parameters
        ----------
        level : str
            Name of the noise level, a key of ``noise_levels``.
        """
        return {**self.table(), "control_strategy": "FS", "noise_level": self.levels[level]}

    def calibration_device(self, device) -> dict:
        """The coarse Table 1 of the calibration's device number ``device``.

        Parameters
        ----------
        device : int or str
            Index of the device in :attr:`calibration_devices`.
        """
        anchorage = self.calibration_devices[int(device)]
        return {"a_max0_g": float(self.config["a_max0"]), **{f"anchorage_{k}": v for k, v in anchorage.items()}}

    def calibration_grid(self) -> dict:
        """The screened grid of the calibration."""
        return {"block_alpha": parameters.block_from_dict(self.config["block"]).alpha,
                "noise_reading": str(self.config["noise"])}

    def calibration_refined(self, rank, strategy: str, level: str) -> dict:
        """The spectrum of the ``rank``-th best screened device under ``strategy`` at ``level``.

        Parameters
        ----------
        rank : int or str
            Rank of the device in the screening, 0 for the best.
        strategy : str
            The control strategy.
        level : str
            Name of the noise level, a key of ``noise_levels``.
        """
        return {**self.table(), "calibration_rank": int(rank), "control_strategy": strategy,
                "noise_level": self.levels[level]}

    # --- beyond the paper -----------------------------------------------------------------------------
    def probability(self, strategy: str, level: str) -> dict:
        """A P(overturn) surface (``beyond.probability``) over the study's realisations.

        Parameters
        ----------
        strategy : str
            The control strategy.
        level : str
            Name of the noise level, a key of ``noise_levels``.
        """
        prob = self.config["beyond"]["probability"]
        return expected_attrs(self.scenario(strategy, level), "spectrum",
                              frequency_ratios=parameters.frequency_ratios(prob["frequency_grid"]),
                              amplitude_grid=prob["amplitude_grid"],
                              n_realisations=int(self.config["realisations"]))

    def record_set(self, name: str, members) -> dict:
        """The record set ``name`` of ``beyond.fragility.records`` with these members.

        Parameters
        ----------
        name : str
            Name of the set (:func:`rockstudy.studies.beyond.record_sets`).
        members : str or list
            The set's config entry (:func:`record_set_members`).
        """
        return {"record_set": name, "record_set_members": record_set_members(members)}

    def fragility(self, name: str) -> dict:
        """The fragility of every strategy over the record set ``name`` (``beyond.fragility``).

        Parameters
        ----------
        name : str
            Name of the record set.
        """
        frag = self.config["beyond"]["fragility"]
        scenario = self.scenario("FS", self.free)
        keep = {"overturn_criterion", "free_time_s"}
        attrs = {k: v for k, v in expected_attrs(scenario).items()
                 if k in keep or k.startswith(("block_", "anchorage_"))}
        return {**attrs, "record_suite": name, "strategy": list(frag["strategies"]),
                "intensity_measure": frag["intensity_measure"],
                "threshold_resolution": float(frag["threshold_resolution"]),
                "n_bootstrap": int(frag["bootstrap"]), "bootstrap_seed": int(frag["seed"])}

    def risk(self, name: str) -> dict:
        """The risk of every strategy of the record set ``name`` at the config's sites (``risk:``).

        Parameters
        ----------
        name : str
            Name of the record set.
        """
        from rockstudy.core.risk_inputs import DEFAULT_GMM, DEFAULT_YEARS
        risk = self.config["risk"]
        return {"record_suite": name, "strategy": list(self.config["beyond"]["fragility"]["strategies"]),
                "years": float(risk.get("years", DEFAULT_YEARS)), "gmm": risk.get("gmm", DEFAULT_GMM)}

    def _design(self) -> dict:
        design = self.config["design"]
        from rockstudy.studies.design import pga_levels
        return {"record_suite": design["suite"], "strategy": list(design["strategies"]),
                "pga_levels_g": [float(v) for v in pga_levels(**design["pga_levels_g"])]}

    def design_block(self, R, alpha) -> dict:
        """One point (R, alpha) of the design's block sweep.

        Parameters
        ----------
        R : float or str
            Half diagonal of the block. [m]
        alpha : float or str
            Slenderness angle. [rad]
        """
        design = self.config["design"]
        return {**self._design(), "R": float(R), "alpha": float(alpha), "excitation": self.config["excitation"],
                "a_max0_g": float(design["blocks"]["a_max0"])}

    def design_device(self, kappa_max, damping_ratio) -> dict:
        """One point (kappa_max, xi) of the design's device sweep, on the study's block.

        Parameters
        ----------
        kappa_max : float or str
            κ_max = 4 K_max b²/(m g R) of the device. [-]
        damping_ratio : float or str
            Damping ratio ξ of the device. [-]
        """
        block = parameters.block_from_dict(self.config["block"])
        return {**self._design(), "kappa_max": float(kappa_max), "damping_ratio": float(damping_ratio),
                **block.to_attrs()}

    def design_blocks(self) -> dict:
        """The gathered block sweep: every R and alpha of ``design.blocks``."""
        blocks = self.config["design"]["blocks"]
        design = self._design()
        return {"record_suite": design["record_suite"], "strategy": design["strategy"],
                "R": sorted(float(r) for r in blocks["R"]), "alpha": sorted(float(a) for a in blocks["alpha"])}

    def design_devices(self) -> dict:
        """The gathered device sweep: every kappa_max and xi of ``design.devices``."""
        devices = self.config["design"]["devices"]
        design = self._design()
        return {"record_suite": design["record_suite"], "strategy": design["strategy"],
                "kappa_max": sorted(float(k) for k in devices["kappa_max"]),
                "damping_ratio": sorted(float(x) for x in devices["damping_ratio"])}


def paired(paths, expectations) -> dict:
    """``{path: expectation}`` of a rule's input files and their expectations, in the same order.

    Parameters
    ----------
    paths : iterable of str or pathlib.Path
        A rule's input files.
    expectations : iterable of dict
        Their expectations (the methods of :class:`StudyExpectations`), in the same order.

    Raises
    ------
    ValueError
        If there are not as many expectations as files.
    """
    paths, expectations = [str(p) for p in paths], list(expectations)
    if len(paths) != len(expectations):
        raise ValueError(f"{len(paths)} input files but {len(expectations)} expectations: {paths}")
    return dict(zip(paths, expectations))
