"""The device calibration: which anchorage brings the CS01 and CS02 rows of Table 1 to the paper's.

The paper publishes no device parameters. With the study's noise reading, a grid of devices
(θ_u/α × κ_min/κ_max × κ_max × ξ, θ_u = θ_K,u = θ_D,u) is screened on a coarse frequency grid with
few realisations, then the best candidates are recomputed with the study's full settings.
Each device gives 12 numbers: J_OS of CS01 and CS02 against the same strategy without noise
and against FS with the same noise, at R001, R005, R010 (Table 1, Eq. 21); the score is the
RMS of their differences to the paper's.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from rockstudy._version import __version__
from rockstudy.analysis.spectra import spectrum
from rockstudy.analysis.utility_index import utility_index
from rockstudy.core import validation
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import Block
from rockstudy.studies.claims import PAPER, PAPER_LEVELS, PAPER_TABLE1
from rockstudy.studies.parameters import noise_free_level, scenario_from_dict
from rockstudy.studies.tables import REFERENCES

STRATEGIES = ("CS01", "CS02")


@dataclass(frozen=True)
class CalibrationDesign:
    """The devices screened: every combination of the listed values.

    The two axes beyond κ_max and ξ are given relative to what they modify, so that every
    combination is a valid device of the model (Eqs. 8–13, 16–17): the "off" stiffness as a share
    of the "on" stiffness (a real variable-stiffness device keeps some stiffness when released;
    κ_min ≤ κ_max always holds), and the ultimate rotation of springs and dampers as a multiple of
    the block's slenderness α (Eqs. 8–11 break the elements at θ_u; the paper's anchorage breaks
    near uplift-to-overturning, θ_u ~ α).

    Parameters
    ----------
    kappa_max : tuple of float
        κ_max = 4·K_max·b²/(m·g·R) values. [-]
    damping_ratio : tuple of float
        ξ values (3·D·b²/(m·R²) = 2ξp). [-]
    ultimate_rotation_ratio : tuple of float, default (1.0,)
        θ_u/α values with θ_u = θ_K,u = θ_D,u; 1 is the library default θ_u = α. [-]
    kappa_min_ratio : tuple of float, default (0.0,)
        κ_min/κ_max values in [0, 1]; 0 releases the spring completely ("off" = no spring). [-]
    """

    kappa_max: tuple
    damping_ratio: tuple
    ultimate_rotation_ratio: tuple = (1.0,)
    kappa_min_ratio: tuple = (0.0,)

    def __post_init__(self):
        for name in ("kappa_max", "damping_ratio", "ultimate_rotation_ratio", "kappa_min_ratio"):
            values = tuple(getattr(self, name))
            if not values or len(set(values)) != len(values):
                raise ValueError(f"CalibrationDesign.{name} must be a non-empty list of distinct values, "
                                 f"got {values!r}")
            for x in values:
                if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
                    raise ValueError(f"CalibrationDesign.{name} values must be finite numbers, got {x!r}")
            object.__setattr__(self, name, tuple(float(x) for x in values))
        for k in self.kappa_max:
            if k < 0:
                raise ValueError(f"CalibrationDesign.kappa_max values must be >= 0, got {k!r}")
        for xi in self.damping_ratio:
            if xi < 0:
                raise ValueError(f"CalibrationDesign.damping_ratio values must be >= 0, got {xi!r}")
        for r in self.kappa_min_ratio:
            if not 0 <= r <= 1:
                raise ValueError(f"CalibrationDesign.kappa_min_ratio values (kappa_min/kappa_max) must lie in "
                                 f"[0, 1], got {r!r}")
        for r in self.ultimate_rotation_ratio:
            if not r > 0:
                raise ValueError(f"CalibrationDesign.ultimate_rotation_ratio values (theta_u/alpha) must be > 0, "
                                 f"got {r!r}")

    @property
    def shape(self) -> tuple:
        """Grid shape (θ_u/α, κ_min/κ_max, κ_max, ξ)."""
        return (len(self.ultimate_rotation_ratio), len(self.kappa_min_ratio), len(self.kappa_max),
                len(self.damping_ratio))

    def devices(self, alpha: float) -> list[dict]:
        """The anchorage dicts (keys of ``Anchorage``) for a block of slenderness ``alpha``.

        Order: θ_u/α outermost, then κ_min/κ_max, κ_max, ξ (C order of :attr:`shape`).

        Parameters
        ----------
        alpha : float
            Slenderness α of the block; each θ_u is its ratio times α. [rad]
        """
        return [device(k, xi, r_th, r_k, alpha) for r_th in self.ultimate_rotation_ratio
                for r_k in self.kappa_min_ratio for k in self.kappa_max for xi in self.damping_ratio]


def device(kappa_max: float, damping_ratio: float, ultimate_rotation_ratio: float, kappa_min_ratio: float,
           alpha: float) -> dict:
    """One anchorage dict: κ_min = ratio·κ_max, θ_K,u = θ_D,u = ratio·α (None, i.e. α, for a ratio of 1).

    Parameters
    ----------
    kappa_max : float
        κ_max = 4·K_max·b²/(m·g·R). [-]
    damping_ratio : float
        ξ. [-]
    ultimate_rotation_ratio : float
        θ_u/α with θ_u = θ_K,u = θ_D,u. [-]
    kappa_min_ratio : float
        κ_min/κ_max, in [0, 1]. [-]
    alpha : float
        Slenderness α of the block. [rad]

    Raises
    ------
    ValueError
        If θ_u = ratio·α exceeds π/2 rad (Eqs. 8–11 need an element that can break before the block lies flat).
    """
    theta = None if ultimate_rotation_ratio == 1.0 else float(ultimate_rotation_ratio) * float(alpha)
    if theta is not None and theta > math.pi / 2:
        raise ValueError(f"calibration ultimate_rotation_ratio = {ultimate_rotation_ratio!r} gives theta_u = "
                         f"{theta:.4g} rad for alpha = {alpha:.4g} rad; allowed is theta_u <= pi/2")
    return {"kappa_max": float(kappa_max), "kappa_min": float(kappa_min_ratio) * float(kappa_max),
            "damping_ratio": float(damping_ratio), "spring_ultimate_rotation": theta,
            "damper_ultimate_rotation": theta}


def paper_rows() -> np.ndarray:
    """The paper's CS01/CS02 rows: array (strategy, reference, noise_level) in % (12 numbers)."""
    return np.array([[PAPER_TABLE1[(ref, s)] for ref in REFERENCES] for s in STRATEGIES], dtype=float)


def rows_of(table: xr.Dataset) -> np.ndarray:
    """CS01/CS02 rows of a Table 1 dataset (:func:`rockstudy.studies.tables.table1`) at R001-R010. [%]

    Parameters
    ----------
    table : xarray.Dataset
        Table 1 with the CS01 and CS02 rows against both references at R001, R005 and R010.
    """
    return np.array([[[float(table["j_os"].sel(reference=ref, strategy=s, noise_level=lv)) for lv in PAPER_LEVELS]
                      for ref in REFERENCES] for s in STRATEGIES])


def score(rows: np.ndarray) -> tuple[float, float]:
    """RMS and largest absolute difference of 12 J_OS values to the paper's. [points of %]

    Parameters
    ----------
    rows : array_like, shape (strategy, reference, noise_level)
        The 12 J_OS values in the layout of :func:`paper_rows`; a NaN gives NaN scores. [%]
    """
    d = np.asarray(rows, float) - paper_rows()
    if np.any(np.isnan(d)):
        return math.nan, math.nan
    return float(np.sqrt(np.mean(d * d))), float(np.max(np.abs(d)))


def conclusions_hold(rows: np.ndarray) -> np.ndarray:
    """Per level: J_OS(CS01 vs FS) > J_OS(CS02 vs FS) > 0 (the paper's ranking). [bool]

    Parameters
    ----------
    rows : array_like, shape (strategy, reference, noise_level)
        The 12 J_OS values in the layout of :func:`paper_rows`. [%]
    """
    vs_fs = np.asarray(rows)[:, REFERENCES.index("fs_same_noise"), :]
    return (vs_fs[0] > vs_fs[1]) & (vs_fs[1] > 0)


GRID_AXES = ("ultimate_rotation_ratio", "kappa_min_ratio", "kappa_max", "damping_ratio")
"""The device axes of a calibration grid, outermost first (the order of :meth:`CalibrationDesign.devices`)."""


def grid_dataset(design: CalibrationDesign, tables, alpha: float, attrs: dict | None = None) -> xr.Dataset:
    """The screened grid: J_OS, residuals, score and the share of devices keeping the paper's ranking.

    Parameters
    ----------
    design : CalibrationDesign
        The screened devices.
    tables : iterable of xarray.Dataset
        Table 1 datasets (:func:`device_table`), one per device in the order of ``design.devices(alpha)``.
    alpha : float
        Slenderness α of the block (θ_u = ratio·α). [rad]
    attrs : dict, optional
        Further global attributes of the dataset.
    """
    shape = design.shape
    nd = len(shape)
    rows = np.array([rows_of(t) for t in tables]).reshape(shape + (2, 2, 3))
    rows = np.moveaxis(rows, (nd, nd + 1, nd + 2), (0, 1, 2))  # (strategy, reference, level, *device axes)
    paper = paper_rows()
    resid = rows - paper.reshape(paper.shape + (1,) * nd)
    rms = np.sqrt(np.mean(resid.reshape(12, -1) ** 2, axis=0)).reshape(shape)
    worst = np.max(np.abs(resid.reshape(12, -1)), axis=0).reshape(shape)
    vs_fs = rows[:, REFERENCES.index("fs_same_noise")]
    holds = (vs_fs[0] > vs_fs[1]) & (vs_fs[1] > 0)  # (level, *device axes)
    dims = ("strategy", "reference", "noise_level") + GRID_AXES
    pct = {"units": "percent"}
    theta = [r * float(alpha) for r in design.ultimate_rotation_ratio]
    return xr.Dataset(
        {"j_os": (dims, rows, {**pct, "long_name": "J_OS (Eq. 21) of the device"}),
         "paper": (dims[:3], paper, {**pct, "long_name": "the paper's Table 1"}),
         "residual": (dims, resid, {**pct, "long_name": "ours minus paper (points)"}),
         "rms_residual": (dims[3:], rms, {**pct, "long_name": "RMS of the 12 residuals"}),
         "max_abs_residual": (dims[3:], worst, {**pct, "long_name": "largest |residual| of the 12"}),
         "ranking_holds": (("noise_level",) + dims[3:], holds.astype(np.int8),
                           {"long_name": "J_OS(CS01 vs FS) > J_OS(CS02 vs FS) > 0"}),
         "ranking_share": ("noise_level", holds.reshape(3, -1).mean(axis=1),
                           {"units": "1", "long_name": "share of the screened devices where CS01 > CS02 > 0 vs FS"})},
        coords={"strategy": list(STRATEGIES), "reference": list(REFERENCES), "noise_level": list(PAPER_LEVELS),
                "ultimate_rotation_ratio": ("ultimate_rotation_ratio", list(design.ultimate_rotation_ratio),
                                            {"units": "1", "long_name": "theta_K,u / alpha = theta_D,u / alpha"}),
                "ultimate_rotation": ("ultimate_rotation_ratio", theta,
                                      {"units": "rad", "long_name": "theta_K,u = theta_D,u"}),
                "kappa_min_ratio": ("kappa_min_ratio", list(design.kappa_min_ratio),
                                    {"units": "1", "long_name": "kappa_min / kappa_max"}),
                "kappa_max": ("kappa_max", list(design.kappa_max), {"units": "1", "long_name": "4 K_max b^2/(m g R)"}),
                "damping_ratio": ("damping_ratio", list(design.damping_ratio), {"units": "1", "long_name": "xi"})},
        attrs={"title": "Device calibration: J_OS of CS01 and CS02 over the screened anchorages", "paper": PAPER,
               "rockstudy_version": __version__, "block_alpha": float(alpha), **(attrs or {})})


def device_at(grid: xr.Dataset, index: tuple) -> dict:
    """The anchorage dict of the grid point ``index`` (positions along :data:`GRID_AXES`).

    Parameters
    ----------
    grid : xarray.Dataset
        The screened grid (:func:`grid_dataset`).
    index : tuple of int
        Positions along :data:`GRID_AXES`.
    """
    values = [float(grid[axis].values[i]) for axis, i in zip(GRID_AXES, index)]
    r_th, r_k, k, xi = values
    return device(k, xi, r_th, r_k, float(grid.attrs["block_alpha"]))


def ordered(values: np.ndarray) -> list[tuple]:
    """Grid indices sorted by ``values`` ascending (NaN last, ties in C order).

    Parameters
    ----------
    values : numpy.ndarray
        Values over the grid's axes (e.g. the RMS residual).
    """
    flat = np.argsort(np.where(np.isnan(values), np.inf, values), axis=None, kind="stable")
    return [tuple(int(i) for i in np.unravel_index(f, values.shape)) for f in flat]


def best_devices(grid: xr.Dataset, n: int) -> list[tuple[dict, float]]:
    """The ``n`` devices with the smallest RMS residual: (anchorage dict, RMS residual [%]), best first.

    Parameters
    ----------
    grid : xarray.Dataset
        The screened grid (:func:`grid_dataset`).
    n : int
        How many devices to return.
    """
    rms = grid["rms_residual"].transpose(*GRID_AXES).values
    return [(device_at(grid, index), float(rms[index])) for index in ordered(rms)[:n]]


def row_distance(grid: xr.Dataset, strategy: str, reference: str) -> xr.DataArray:
    """RMS over the three levels of one row of Table 1 (e.g. CS02 against no noise) to the paper's. [points]

    Parameters
    ----------
    grid : xarray.Dataset
        The screened grid (:func:`grid_dataset`).
    strategy : {"CS01", "CS02"}
        The row's strategy.
    reference : {"no_noise", "fs_same_noise"}
        The row's reference.
    """
    resid = grid["residual"].sel(strategy=strategy, reference=reference)
    return np.sqrt((resid ** 2).mean("noise_level", skipna=False))


def physical(block: Block, anchorage: Anchorage) -> dict:
    """K_max [N/m], K_min [N/m], D [N s/m] and θ_u [rad] a device means for ``block``.

    Parameters
    ----------
    block : rockstudy.model.block.Block
        The block the device anchors.
    anchorage : rockstudy.model.anchorage.Anchorage
        The dimensionless device.
    """
    return {"K_max_N_per_m": anchorage.K_max(block), "K_min_N_per_m": anchorage.K_min(block),
            "D_N_s_per_m": anchorage.D(block), "theta_K_u_rad": anchorage.theta_spring(block),
            "theta_D_u_rad": anchorage.theta_damper(block)}


def candidates_dataset(block: Block, devices: list[dict], tables, coarse_rms, attrs: dict | None = None) -> xr.Dataset:
    """The refined candidates: their 12 J_OS values, residuals, score and physical parameters.

    Parameters
    ----------
    block : rockstudy.model.block.Block
        The study's block (for the physical parameters).
    devices : list of dict
        The candidates' anchorage dicts (:func:`device`), best of the screening first.
    tables : iterable of xarray.Dataset
        Table 1 of each candidate with the study's full settings (:func:`device_table`), in the same order.
    coarse_rms : array_like of float
        Each candidate's RMS residual in the coarse screening. [%]
    attrs : dict, optional
        Further global attributes of the dataset.
    """
    rows = np.array([rows_of(t) for t in tables])  # (candidate, strategy, reference, level)
    resid = rows - paper_rows()[None]
    anchorages = [Anchorage(**d) for d in devices]
    phys = [physical(block, a) for a in anchorages]
    dims = ("candidate", "strategy", "reference", "noise_level")
    pct = {"units": "percent"}
    data = {
        "j_os": (dims, rows, {**pct, "long_name": "J_OS (Eq. 21), full settings"}),
        "paper": (dims[1:], paper_rows(), {**pct, "long_name": "the paper's Table 1"}),
        "residual": (dims, resid, {**pct, "long_name": "ours minus paper (points)"}),
        "rms_residual": ("candidate", np.sqrt(np.mean(resid.reshape(len(devices), -1) ** 2, axis=1)),
                         {**pct, "long_name": "RMS of the 12 residuals"}),
        "max_abs_residual": ("candidate", np.max(np.abs(resid.reshape(len(devices), -1)), axis=1),
                             {**pct, "long_name": "largest absolute residual"}),
        "coarse_rms_residual": ("candidate", np.asarray(coarse_rms, float),
                                {**pct, "long_name": "RMS residual in the coarse screening"}),
        "kappa_max": ("candidate", [a.kappa_max for a in anchorages],
                      {"units": "1", "long_name": "4 K_max b^2/(m g R)"}),
        "kappa_min": ("candidate", [a.kappa_min for a in anchorages],
                      {"units": "1", "long_name": "4 K_min b^2/(m g R)"}),
        "damping_ratio": ("candidate", [a.damping_ratio for a in anchorages], {"units": "1", "long_name": "xi"}),
    }
    for key, unit, name in (("K_max_N_per_m", "N/m", "spring stiffness K_max"),
                            ("K_min_N_per_m", "N/m", "spring stiffness K_min"),
                            ("D_N_s_per_m", "N s/m", "damper coefficient D"),
                            ("theta_K_u_rad", "rad", "ultimate rotation of the spring"),
                            ("theta_D_u_rad", "rad", "ultimate rotation of the damper")):
        data[key] = ("candidate", [p[key] for p in phys], {"units": unit, "long_name": name})
    candidate = ("candidate", np.arange(len(devices)), {"long_name": "rank of the candidate in the screening"})
    return xr.Dataset(data, coords={"candidate": candidate, "strategy": list(STRATEGIES),
                                    "reference": list(REFERENCES), "noise_level": list(PAPER_LEVELS)},
                      attrs={"title": "Device calibration: best candidates recomputed with the study's settings",
                             "paper": PAPER, "rockstudy_version": __version__, **block.to_attrs(), **(attrs or {})})


def calibration_markdown(grid: xr.Dataset, candidates: xr.Dataset | None = None, runtime_s: float | None = None) -> str:
    """Summary: best devices with their 12 residuals and physical parameters, the ranking share.

    Parameters
    ----------
    grid : xarray.Dataset
        The screened grid (:func:`grid_dataset`).
    candidates : xarray.Dataset, optional
        The refined candidates (:func:`candidates_dataset`); None: the section is left out.
    runtime_s : float, optional
        Run time of the calibration jobs; None: not stated. [s]
    """
    out = ["# Device calibration", ""]
    out.append("Share of screened devices where J_OS(CS01 vs FS) > J_OS(CS02 vs FS) > 0: " + ", ".join(
        f"{lv} {100 * float(v):.0f} %" for lv, v in zip(grid["noise_level"].values, grid["ranking_share"].values))
        + f" (of {int(grid['rms_residual'].size)} devices).")
    out.append("")
    rms = grid["rms_residual"].transpose(*GRID_AXES).values
    cs02_row = row_distance(grid, "CS02", "no_noise").transpose(*GRID_AXES).values
    positive = (grid["j_os"].sel(strategy="CS02", reference="no_noise") > 0).all("noise_level")
    out += ["## Screening (coarse)", "",
            f"Devices whose CS02 row against no noise is positive at all three levels (the paper: "
            f"{', '.join(f'{v:+.2f}' for v in grid['paper'].sel(strategy='CS02', reference='no_noise').values)} %): "
            f"{int(positive.sum())} of {int(positive.size)}.", ""]
    head = "| theta_u/alpha | kappa_min/kappa_max | kappa_max | xi | RMS residual | max abs residual | " \
           "CS02 vs no noise R001/R005/R010 | its RMS to the paper's |"
    out += [head, "|---|---|---|---|---|---|---|---|"]
    for index in ordered(rms):
        sel = dict(zip(GRID_AXES, index))
        cs02 = grid["j_os"].isel(**sel).sel(strategy="CS02", reference="no_noise").values
        axes = [float(grid[a].values[i]) for a, i in sel.items()]
        out.append("| " + " | ".join(f"{x:g}" for x in axes) + f" | {float(rms[index]):.2f} | "
                   f"{float(grid['max_abs_residual'].isel(**sel)):.2f} | " + "/".join(f"{v:+.2f}" for v in cs02)
                   + f" | {float(cs02_row[index]):.2f} |")
    if candidates is not None:
        out += ["", "## Candidates with the study's full settings", ""]
        for c in candidates["candidate"].values:
            t = candidates.sel(candidate=c)
            out.append(f"### Candidate {int(c)}: kappa_max = {float(t['kappa_max']):g}, kappa_min = "
                       f"{float(t['kappa_min']):g}, xi = {float(t['damping_ratio']):g}, theta_u = "
                       f"{float(t['theta_K_u_rad']):.3f} rad "
                       f"(K_max = {float(t['K_max_N_per_m']) / 1000:.1f} kN/m, K_min = "
                       f"{float(t['K_min_N_per_m']) / 1000:.1f} kN/m, D = "
                       f"{float(t['D_N_s_per_m']) / 1000:.2f} kN s/m for this block)")
            out.append(f"RMS residual {float(t['rms_residual']):.2f}, max {float(t['max_abs_residual']):.2f} points "
                       f"(coarse screening: {float(t['coarse_rms_residual']):.2f}).")
            out += ["", "| row | R001 paper / ours / diff | R005 | R010 |", "|---|---|---|---|"]
            for s in STRATEGIES:
                for ref in REFERENCES:
                    cells = [f"{float(t['paper'].sel(strategy=s, reference=ref, noise_level=lv)):+.2f} / "
                             f"{float(t['j_os'].sel(strategy=s, reference=ref, noise_level=lv)):+.2f} / "
                             f"{float(t['residual'].sel(strategy=s, reference=ref, noise_level=lv)):+.2f}"
                             for lv in PAPER_LEVELS]
                    out.append(f"| {s} vs {ref} | " + " | ".join(cells) + " |")
            out.append("")
    if runtime_s is not None:
        out += ["", f"Run time of the calibration jobs (sum of their benchmarks): {runtime_s:.0f} s."]
    return "\n".join(out) + "\n"


def device_spectra(scenario_spec: dict, anchorage: dict, strategies, levels: dict, frequency_ratios,
                   realisations: int, grid) -> list[xr.Dataset]:
    """Spectra of one device for each strategy and noise level (the noise-free level with one realisation).

    Parameters
    ----------
    scenario_spec : dict
        A :func:`rockstudy.studies.parameters.scenario_from_dict` dict without ``anchorage``, ``control`` and
        ``noise_level``, optionally with ``control_options`` (the config's ``control:`` keys, e.g. the sensor,
        applied to every strategy).
    anchorage : dict
        The device: keyword arguments of :class:`~rockstudy.model.anchorage.Anchorage` (:func:`device`).
    strategies : iterable of str
        The control strategies, e.g. ``("CS01", "CS02")``.
    levels : dict
        Level name -> noise level. [-]
    frequency_ratios : array_like of float
        ω_p/p of the spectra. [-]
    realisations : int
        Noise realisations of each noisy spectrum (the noise-free one has one).
    grid : rockstudy.analysis.spectra.AmplitudeGrid
        The amplitude scan.
    """
    spec = {k: v for k, v in scenario_spec.items() if k != "control_options"}
    options = dict(scenario_spec.get("control_options") or {})
    out = []
    for s in strategies:
        for level in levels.values():
            sc = scenario_from_dict({**spec, "anchorage": anchorage, "control": {"strategy": s, **options},
                                     "noise_level": float(level)})
            out.append(spectrum(sc, frequency_ratios, realisations=range(realisations if level > 0 else 1),
                                grid=grid, progress_chunks=2))
    return out


def device_table(fs_spectra, device_spectra_list, levels: dict, a_max0_g: float) -> xr.Dataset:
    """Table 1 (FS, CS01, CS02) of one device from its spectra and the FS spectra on the same grid.

    A J_OS that Eq. 21 leaves undefined (N* = 0: neither spectrum overturns below a_max,0 at any
    frequency, e.g. a stiff device with and without noise) is NaN; such a device gets no score.

    Parameters
    ----------
    fs_spectra : iterable of xarray.Dataset
        Spectra of the free-standing block at every level, on the same grid; the first one's ``block_alpha``
        converts a_max,0.
    device_spectra_list : iterable of xarray.Dataset
        The device's spectra (:func:`device_spectra`).
    levels : dict
        Level name -> noise level; it must hold the paper's R001, R005, R010 and one level equal to 0. [-]
    a_max0_g : float
        Protection level a_max,0. [g]
    """
    missing = [lv for lv in PAPER_LEVELS if lv not in levels]
    if missing:
        raise ValueError(f"noise_levels: the calibration needs the paper's levels {PAPER_LEVELS}, missing {missing}")
    spectra = list(fs_spectra) + list(device_spectra_list)

    def find(strategy, value):
        for ds in spectra:
            if ds["strategy"].item() == strategy and math.isclose(float(ds["noise_level"]), value, abs_tol=1e-12):
                return ds
        raise KeyError(f"no {strategy} spectrum at noise level {value}")

    free = levels[noise_free_level(levels)]
    ratio = float(a_max0_g) / math.tan(float(spectra[0].attrs["block_alpha"]))
    strategies = ["FS"] + sorted({ds["strategy"].item() for ds in device_spectra_list})
    j = np.full((2, len(strategies), len(PAPER_LEVELS)), np.nan)
    for si, s in enumerate(strategies):
        for li, lv in enumerate(PAPER_LEVELS):
            system = find(s, levels[lv])
            refs = [find(s, free), None if s == "FS" else find("FS", levels[lv])]
            for ri, ref in enumerate(refs):
                if ref is None:
                    continue
                try:
                    j[ri, si, li] = utility_index(system["threshold"].values, ref["threshold"].values, ratio)[0]
                except ValueError:  # N* = 0: J_OS undefined
                    j[ri, si, li] = math.nan
    table = xr.Dataset({"j_os": (("reference", "strategy", "noise_level"), j,
                                 {"units": "percent", "long_name": "utility index J_OS (Eq. 21)"})},
                       coords={"reference": list(REFERENCES), "strategy": strategies,
                               "noise_level": list(PAPER_LEVELS)},
                       attrs={"a_max0_g": float(a_max0_g), "rockstudy_version": __version__})
    table.attrs["compute_time_s"] = float(sum(ds.attrs.get("compute_time_s", 0.0) for ds in device_spectra_list))
    return table


def check_config(section: dict, alpha: float, sims_per_case: int | None = None) -> None:
    """The config's ``calibration:`` section describes valid devices for a block of slenderness ``alpha``:
    every value within the anchorage's limits, at most :data:`~rockstudy.core.validation.MAX_DEVICES`
    devices, ``candidates`` among them, the coarse realisations and frequency grid within the limits and,
    given ``sims_per_case`` (simulations of one threshold), a coarse job within the workload limit.

    Parameters
    ----------
    section : dict
        The config's ``calibration:`` section.
    alpha : float
        Slenderness α of the study's block. [rad]
    sims_per_case : int, optional
        Simulations of one threshold (the amplitude scan); None: the coarse job's workload is not checked.

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) naming ``calibration.<key>`` and what is wrong.
    """
    for key, high, why in (("kappa_max", validation.MAX_KAPPA, ""), ("damping_ratio", validation.MAX_DAMPING_RATIO, ""),
                           ("ultimate_rotation_ratio", math.pi / 2 / alpha,
                            "theta_u = ratio x alpha <= pi/2, alpha of the block"),
                           ("kappa_min_ratio", 1.0, "kappa_min <= kappa_max")):
        for i, value in enumerate(section[key]):
            validation.check_nonnegative(f"calibration.{key}[{i}]", value, high=high, why=why)
    n_devices = math.prod(len(section[k]) for k in ("kappa_max", "damping_ratio", "ultimate_rotation_ratio",
                                                      "kappa_min_ratio"))
    if n_devices > validation.MAX_DEVICES:
        validation.fail("calibration", f"{n_devices} devices",
                        f"at most {validation.MAX_DEVICES} (every combination of kappa_max, damping_ratio, "
                        "ultimate_rotation_ratio, kappa_min_ratio)")
    validation.check_int_range("calibration.candidates", section["candidates"], 1, n_devices,
                               why="the best of the devices screened: every combination of calibration.kappa_max, "
                                   ".damping_ratio, .ultimate_rotation_ratio, .kappa_min_ratio")
    n_real = validation.check_int_range("calibration.coarse_realisations", section["coarse_realisations"], 1,
                               validation.MAX_REALISATIONS)
    fg = section["coarse_frequency_grid"]
    n_freq = validation.check_grid("calibration.coarse_frequency_grid", fg["start"], fg["stop"], fg["step"],
                          high=validation.MAX_FREQUENCY_RATIO)
    if sims_per_case is not None:
        validation.check_workload("calibration.coarse_realisations", n_real, n_real * n_freq, sims_per_case, 0)
    try:
        design = CalibrationDesign(section["kappa_max"], section["damping_ratio"], section["ultimate_rotation_ratio"],
                                   section["kappa_min_ratio"])
        design.devices(alpha)
    except ValueError as exc:
        raise validation.InputError(f"calibration: {exc}") from None
