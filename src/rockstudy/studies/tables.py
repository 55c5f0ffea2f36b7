"""J_OS tables (paper Eq. 21, Table 1 and the timing sweeps of §5.2): Table 1 against both references,
the timing tables, and their Markdown and CSV forms, each cell from :func:`rockstudy.analysis.jos.jos`.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from rockstudy._version import __version__
from rockstudy.analysis.jos import jos
from rockstudy.studies.datasets import MISSING_MEANINGS, PAPER
from rockstudy.studies.parameters import noise_free_level

REFERENCES = ("no_noise", "fs_same_noise")


"""Table 1's two references: the same strategy without noise, and FS at the same noise level."""


SPECTRUM_NUMBERS = ("block_alpha", "grid_amplitude_start", "grid_amplitude_stop", "grid_amplitude_step")
"""Attributes J_OS needs from a spectrum file (a_max,0 as a ratio, the scan's top)."""
JOS_SETTINGS = ("excitation", "overturn_criterion", "free_time_s", "grid_amplitude_start", "grid_amplitude_stop",
                "grid_amplitude_step", "grid_amplitude_resolution")
"""Settings two spectra compared by J_OS must share besides the block and the device (``block_*``,
``anchorage_*``) and the frequency grid."""
NOISY_SETTINGS = ("noise_seed", "noise_step_s", "noise_rescale", "noise_level_means", "noise_band_hz",
                  "noise_span_s", "n_realisations")
"""Settings two noisy spectra must also share: the noise reading, the seed and the number of realisations
(a noise-free spectrum does not depend on them)."""


def check_spectrum_file(ds: xr.Dataset, name: str) -> None:
    """``ds`` is a rockstudy spectrum J_OS can use: a 1-D ``threshold`` over ``frequency_ratio`` and finite
    block slenderness (0 < block_alpha < pi/2) and amplitude scan attributes.

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset read from the file.
    name : str
        The file's name, as the messages give it.

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) naming ``name`` and what is missing or wrong.
    """
    import math

    from rockstudy.core import validation
    if "threshold" not in ds or "frequency_ratio" not in ds.coords or ds["threshold"].dims != ("frequency_ratio",):
        raise validation.InputError(f"{name}: not a rockstudy spectrum file (no 'threshold' over 'frequency_ratio')")
    freqs = ds["frequency_ratio"].values
    if freqs.size == 0 or not np.all(np.isfinite(freqs)) or np.any(freqs <= 0):
        raise validation.InputError(f"{name}: frequency_ratio must be non-empty, finite and > 0")
    for key in SPECTRUM_NUMBERS:
        if key not in ds.attrs:
            raise validation.InputError(f"{name}: not a rockstudy spectrum file (no attribute {key!r})")
        try:
            value = float(np.asarray(ds.attrs[key]).item())
        except (TypeError, ValueError):
            raise validation.InputError(f"{name}: attribute {key} = {ds.attrs[key]!r} is not a number") from None
        high = math.pi / 2 if key == "block_alpha" else validation.MAX_AMPLITUDE_RATIO
        if not (math.isfinite(value) and 0 < value < high):
            raise validation.InputError(f"{name}: attribute {key} = {value!r} is not allowed: it must lie in "
                                        f"(0, {high:g})")
    try:
        level = _level(ds)
    except (TypeError, ValueError):
        raise validation.InputError(f"{name}: noise_level is not a number") from None
    if not 0 <= level < 1:
        raise validation.InputError(f"{name}: noise_level = {level!r} is not allowed: it must lie in [0, 1)")
    if ds.attrs["grid_amplitude_stop"] < ds.attrs["grid_amplitude_start"]:
        raise validation.InputError(f"{name}: grid_amplitude_stop is below grid_amplitude_start")


def _level(ds: xr.Dataset) -> float:
    return float(ds["noise_level"]) if "noise_level" in ds.variables else float(ds.attrs.get("noise_level", 0.0))


def _setting(ds: xr.Dataset, key: str):
    if key == "n_realisations":
        return int(ds.sizes.get("realisation", 1))
    value = ds.attrs.get(key, "<missing>")
    return value.tolist() if isinstance(value, (np.ndarray, np.generic)) else value


def spectrum_mismatches(system: xr.Dataset, reference: xr.Dataset) -> list[tuple[str, object, object]]:
    """(attribute, system's value, reference's value) of every setting in which two spectra differ and that
    J_OS needs equal: the block, the device, :data:`JOS_SETTINGS` and, when both are noisy,
    :data:`NOISY_SETTINGS`. The strategy, its timing and sensor, and the noise level may differ: they are
    what J_OS compares.

    Parameters
    ----------
    system, reference : xarray.Dataset
        The two spectra J_OS compares (:func:`rockstudy.analysis.jos.jos`).
    """
    from rockstudy.core.io import same_value
    keys = sorted({k for ds in (system, reference) for k in ds.attrs if k.startswith(PROVENANCE_PREFIXES)},
                  key=lambda k: (not k.startswith("block_"), k))  # the block first: the device's attrs follow it
    keys += list(JOS_SETTINGS)
    if _level(system) > 0 and _level(reference) > 0:
        keys += list(NOISY_SETTINGS)
    out = []
    for key in keys:
        a, b = _setting(system, key), _setting(reference, key)
        if not same_value(a, b):
            out.append((key, a, b))
    return out


def _jos(system: xr.Dataset, reference: xr.Dataset, a_max0_g: float) -> tuple[float, int]:
    result = jos(system, reference, a_max0_g)
    return result.j_os, result.n_star


PROVENANCE_PREFIXES = ("block_", "anchorage_")


PROVENANCE_KEYS = ("noise_seed", "excitation", "overturn_criterion", "free_time_s",
                   "grid_amplitude_start", "grid_amplitude_stop", "grid_amplitude_step", "grid_amplitude_resolution",
                   "noise_step_s", "noise_rescale", "noise_level_means", "noise_band_hz", "noise_span_s")


def provenance(spectra) -> dict:
    """Attributes a table inherits from the spectra it compares: the seed, the block, the device
    (anchorage), the excitation and scan, and the number of noise realisations of the noisy spectra.

    Parameters
    ----------
    spectra : sequence of xarray.Dataset
        The spectra the table compares: the first gives the seed, block, device, excitation and scan, the
        noisy ones (``noise_level`` > 0) the number of realisations.
    """
    first = spectra[0]
    attrs = {k: val for k, val in first.attrs.items() if k.startswith(PROVENANCE_PREFIXES) or k in PROVENANCE_KEYS}
    noisy = sorted({int(ds.sizes["realisation"]) for ds in spectra if float(ds["noise_level"]) > 0})
    attrs["n_realisations"] = noisy[0] if len(noisy) == 1 else str(noisy)
    attrs["n_realisations_note"] = "noise realisations of each noisy spectrum (a noise-free spectrum has one)"
    return attrs


def _find(datasets, **coords) -> xr.Dataset:
    for ds in datasets:
        if all(np.isclose(float(ds[k]), v) if not isinstance(v, str) else ds[k].item() == v
               for k, v in coords.items()):
            return ds
    raise KeyError(f"no spectrum with {coords}")


def _table(values: np.ndarray, n_star: np.ndarray, coords: dict, attrs: dict) -> xr.Dataset:
    dims = tuple(coords)
    return xr.Dataset(
        {"j_os": (dims, values, {"units": "percent", "long_name": "utility index J_OS, Eq. 21",
                                 "missing_value_meaning": MISSING_MEANINGS["j_os"]}),
         "n_star": (dims, n_star, {"units": "1", "long_name": "N*, frequencies counted in Eq. 21"})},
        coords={k: (k, list(v)) for k, v in coords.items()},
        attrs={"paper": PAPER, "rockstudy_version": __version__, **attrs})


def table1(spectra, strategies, noise_levels: dict, a_max0_g: float) -> xr.Dataset:
    """Table 1: J_OS of each strategy at each noisy level against (a) the same strategy without
    noise and (b) the free-standing block at the same noise level (for FS itself J_OS = 0 over the
    N* frequencies where it overturns below a_max,0, as ``rockstudy jos`` gives; NaN only where N* = 0).

    Parameters
    ----------
    spectra : iterable of xarray.Dataset
        Overturning spectra with scalar ``strategy`` and ``noise_level`` coordinates: every strategy at
        every level, and FS at every noisy level.
    strategies : sequence of str
        The strategies of the table's rows, in order.
    noise_levels : dict
        Noise level name -> value (noise energy over baseline energy); the level equal to 0 is the
        reference without noise, the others are the table's columns. [-]
    a_max0_g : float
        Protection level a_max,0. [g]
    """
    free = noise_free_level(noise_levels)
    noisy = [name for name in noise_levels if name != free]
    j = np.full((len(REFERENCES), len(strategies), len(noisy)), np.nan)
    n = np.zeros(j.shape, dtype=np.int64)
    for si, s in enumerate(strategies):
        for li, name in enumerate(noisy):
            system = _find(spectra, strategy=s, noise_level=noise_levels[name])
            refs = [_find(spectra, strategy=s, noise_level=0.0),
                    _find(spectra, strategy="FS", noise_level=noise_levels[name])]
            for ri, ref in enumerate(refs):
                j[ri, si, li], n[ri, si, li] = _jos(system, ref, a_max0_g)
    return _table(j, n, {"reference": REFERENCES, "strategy": strategies, "noise_level": noisy},
                  {"title": "Table 1: utility index J_OS at each noise level", "paper_table": "1",
                   "a_max0_g": a_max0_g, "reference_meanings": "no_noise: same strategy without noise (R000); "
                   "fs_same_noise: free-standing block at the same noise level",
                   "noise_level_values": str(noise_levels), **provenance(spectra)})


TIMING_LONG_NAMES = {"sampling_time": "sampling time T_s of the controller",
                     "delay": "actuation delay of the controller"}
"""Long names of the timing tables' last coordinate."""


def timing_table(sweep, same_strategy, free_standing, variable: str, a_max0_g: float,
                 reference: str = "continuous_same_noise") -> xr.Dataset:
    """J_OS of sampled (or delayed) control against the same strategy without that timing
    (``same_strategy``: continuous control, or sampled without delay) and against the
    free-standing block, both at the sweep's noise level (§5.2, Figs. 7–8).

    Parameters
    ----------
    sweep : sequence of xarray.Dataset
        Spectra of the timing sweep, each with scalar ``strategy``, ``noise_level`` and ``sampling_time``
        coordinates and the coordinate named ``variable``.
    same_strategy : iterable of xarray.Dataset
        The references without that timing (continuous control, or sampled without delay), by strategy and
        noise level.
    free_standing : iterable of xarray.Dataset
        Spectra of the free-standing block (FS), by noise level.
    variable : str
        Name of the swept coordinate, ``"sampling_time"`` or ``"delay"`` (its values in s).
    a_max0_g : float
        Protection level a_max,0. [g]
    reference : str, default "continuous_same_noise"
        Label of the ``same_strategy`` reference on the table's ``reference`` coordinate.
    """
    strategies = sorted({ds["strategy"].item() for ds in sweep})
    values = sorted({float(ds[variable]) for ds in sweep})
    j = np.full((len(REFERENCES), len(strategies), len(values)), np.nan)
    n = np.zeros(j.shape, dtype=np.int64)
    for ds in sweep:
        s, si, vi = ds["strategy"].item(), strategies.index(ds["strategy"].item()), values.index(float(ds[variable]))
        level = float(ds["noise_level"])
        refs = [_find(same_strategy, strategy=s, noise_level=level), _find(free_standing, noise_level=level)]
        for ri, ref in enumerate(refs):
            j[ri, si, vi], n[ri, si, vi] = _jos(ds, ref, a_max0_g)
    out = _table(j, n, {"reference": (reference, "fs_same_noise"), "strategy": strategies,
                        variable: values},
                 {"title": f"J_OS against {variable} (§5.2)", "a_max0_g": a_max0_g,
                  "sampling_time_s": str(sorted({float(d['sampling_time']) for d in sweep})),
                  "noise_level": str(sorted({float(d['noise_level']) for d in sweep})),
                  **provenance(list(sweep) + list(same_strategy) + list(free_standing))})
    out[variable].attrs = {"units": "s", "long_name": TIMING_LONG_NAMES.get(variable, variable)}
    return out


def table_markdown(table: xr.Dataset) -> str:
    """The table as Markdown: rows strategies, columns reference × last dimension, J_OS in %.

    Parameters
    ----------
    table : xarray.Dataset
        A J_OS table of :func:`table1` or :func:`timing_table`.
    """
    column = table["j_os"].dims[-1]
    head = ["strategy"] + [f"{r}: {c}" for r in table["reference"].values for c in table[column].values]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for s in table["strategy"].values:
        cells = [f"{v:+.2f}%" if np.isfinite(v) else "-"
                 for r in table["reference"].values for v in table["j_os"].sel(reference=r, strategy=s).values]
        lines.append("| " + " | ".join([str(s)] + cells) + " |")
    return f"{table.attrs.get('title', '')}\n\n" + "\n".join(lines) + "\n"


def table_csv(table: xr.Dataset) -> str:
    """The table in long form: one row per (reference, strategy, column) with J_OS [%] and N*.

    Parameters
    ----------
    table : xarray.Dataset
        A J_OS table of :func:`table1` or :func:`timing_table`.
    """
    return table.to_dataframe().reset_index().to_csv(index=False, float_format="%.4f")
