"""Figures of the paper from the workflow's netCDF outputs (the only package using matplotlib).

Axis-level functions take an ``ax`` and return the artists they draw; ``figure_*`` functions
compose the paper's multi-panel figures from those and return the :class:`Figure`.
Frequencies are ω_p/p, amplitudes a_p/(g·tanα).

One module per family of figures, all drawn in the one style of :mod:`~rockstudy.plotting.style`:

- :mod:`~rockstudy.plotting.spectra`: thresholds against ω_p/p (Figs. 5–8);
- :mod:`~rockstudy.plotting.histories`: time histories and the excitation (Figs. 2–4);
- :mod:`~rockstudy.plotting.maps`: outcome and probability maps over the (ω_p/p, a_p) plane;
- :mod:`~rockstudy.plotting.records`: fragility curves and every record's threshold;
- :mod:`~rockstudy.plotting.design`: the block and device design charts;
- :mod:`~rockstudy.plotting.risk`: risk at a site (hazard curves, fragilities used, disaggregation);
- :mod:`~rockstudy.plotting.calibration`: the noise readings and the device calibration grid;
- :mod:`~rockstudy.plotting.save`: :func:`save_figure`.

Every public name is importable from ``rockstudy.plotting`` itself.
"""
from rockstudy.plotting.style import (  # noqa: I001  (the style module selects the Agg backend first)
    AMPLITUDE_LABEL,
    CURVE_COLOURS,
    CURVE_DASHES,
    CURVE_WIDTH,
    FREQUENCY_LABEL,
    INTENSITY_LABELS,
    OKABE_ITO,
    OUTCOME_COLOURS,
    REFERENCE_STYLE,
    STRATEGY_COLOURS,
    STRATEGY_MARKERS,
    STYLE,
    level_label,
    plain_text,
    styled,
)
from rockstudy.plotting.calibration import figure_calibration, figure_readings, plot_readings
from rockstudy.plotting.design import (
    figure_design_devices,
    figure_design_jos_maps,
    figure_design_size_effect,
    figure_design_winner,
    plot_design_map,
)
from rockstudy.plotting.histories import (
    figure_control_history,
    figure_excitation,
    plot_excitation,
    plot_history,
    plot_stiffness,
    velocity_with_impacts,
)
from rockstudy.plotting.maps import figure_maps, figure_probability, plot_outcome_map, plot_probability
from rockstudy.plotting.risk import (
    figure_risk,
    plot_disaggregation,
    plot_hazard_curves,
    plot_risk_fragilities,
    plot_scenario_probabilities,
)
from rockstudy.plotting.records import (
    figure_fragility,
    figure_record_thresholds,
    pga_in_g_axis,
    plot_fragility,
    plot_median_shift,
    plot_record_thresholds,
)
from rockstudy.plotting.save import save_figure
from rockstudy.plotting.spectra import (
    ABOVE_GID,
    figure_noise_sensitivity,
    figure_realisations,
    figure_spectrum,
    figure_timing,
    group_same_curves,
    plot_a_max0,
    plot_threshold,
    plot_threshold_family,
    same_curve,
    spectrum_axes,
    spectrum_legend,
)

__all__ = [
    "ABOVE_GID", "AMPLITUDE_LABEL", "CURVE_COLOURS", "CURVE_DASHES", "CURVE_WIDTH", "FREQUENCY_LABEL",
    "INTENSITY_LABELS", "OKABE_ITO", "OUTCOME_COLOURS", "REFERENCE_STYLE", "STRATEGY_COLOURS", "STRATEGY_MARKERS",
    "STYLE", "figure_calibration", "figure_control_history", "figure_design_devices", "figure_design_jos_maps",
    "figure_design_size_effect", "figure_design_winner", "figure_excitation", "figure_fragility", "figure_maps",
    "figure_noise_sensitivity", "figure_probability", "figure_readings", "figure_realisations", "figure_risk",
    "plot_disaggregation", "plot_hazard_curves", "plot_risk_fragilities", "plot_scenario_probabilities",
    "figure_record_thresholds", "figure_spectrum", "figure_timing", "group_same_curves", "level_label",
    "pga_in_g_axis", "plain_text", "plot_a_max0", "plot_design_map", "plot_excitation", "plot_fragility",
    "plot_history", "plot_median_shift", "plot_outcome_map", "plot_probability", "plot_readings",
    "plot_record_thresholds", "plot_stiffness", "plot_threshold", "plot_threshold_family", "same_curve",
    "save_figure", "spectrum_axes", "spectrum_legend", "styled", "velocity_with_impacts"
]
