# Figures (PNG for the report, PDF for print), drawn only from the netCDF outputs.

FIG6_PANELS = [s for s in ("FS", "CS01", "CS02") if s in config["strategies"]]  # Fig. 6b-d
CONVERGENCE_FILE = f"{OUT}/convergence/{config['convergence']['strategy']}_{config['convergence']['noise_level']}.nc"
CONVERGENCE = {CONVERGENCE_FILE: EXPECT.spectrum(config["convergence"]["strategy"], config["convergence"]["noise_level"])}
"""The convergence file of Fig. 6a and of the claims, and its expectation."""


rule figure_history:
    input:
        get_control_history_file,
    output:
        png=report(f"{OUT}/figures/fig{{fignum}}_history_{{strategy}}.png", caption="../report/fig_history.rst",
                   category="Figures", subcategory="Control strategies (Figs. 2-3)",
                   labels=report_pages.labels("Time history under {strategy}, noise-free", "Fig. {fignum}")),
        pdf=f"{OUT}/figures/fig{{fignum}}_history_{{strategy}}.pdf",
    log:
        f"{OUT}/logs/figures/fig{{fignum}}_history_{{strategy}}.log",
    params:
        expect=expect_control_history,
        plotting=PLOTTING,
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/figure_history.py"


rule figure_excitation:
    input:
        f"{OUT}/noise/{max(NOISY, key=LEVELS.get)}.nc",
    output:
        png=report(f"{OUT}/figures/fig4_excitation.png", caption="../report/fig4.rst", category="Figures",
                   subcategory="Noise (Figs. 4-6)",
                   labels=report_pages.labels("The excitation of Eq. 23, without and with noise", "Fig. 4")),
        pdf=f"{OUT}/figures/fig4_excitation.pdf",
    log:
        f"{OUT}/logs/figures/fig4_excitation.log",
    params:
        expect=expected([f"{OUT}/noise/{max(NOISY, key=LEVELS.get)}.nc"], [EXPECT.noise(max(NOISY, key=LEVELS.get))]),
        plotting=PLOTTING,
        noise_level=max(NOISY, key=LEVELS.get),
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/figure_excitation.py"


rule figure_realisations:
    input:
        spectrum=spectrum_files([EX["strategy"]], [EX["noise_level"]]),
        histories=EX_HISTORIES,
    output:
        png=report(f"{OUT}/figures/fig5_realisations.png", caption="../report/fig5.rst", category="Figures",
                   subcategory="Noise (Figs. 4-6)",
                   labels=report_pages.labels("Thresholds of two noise realisations and the example point", "Fig. 5")),
        pdf=f"{OUT}/figures/fig5_realisations.pdf",
    log:
        f"{OUT}/logs/figures/fig5_realisations.log",
    params:
        expect=report_pages.ExpectedAttributes({**expected(spectrum_files([EX["strategy"]], [EX["noise_level"]]),
                           spectra_expected([EX["strategy"]], [EX["noise_level"]])),
                **expected(EX_HISTORIES, EX_HISTORIES_EXPECTED)}),
        plotting=PLOTTING,
        point=EX,
        a_max0=config["a_max0"],
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/figure_realisations.py"


rule figure_noise_sensitivity:
    input:
        convergence=CONVERGENCE_FILE,
        spectra=spectrum_files(FIG6_PANELS, LEVELS),
    output:
        png=report(f"{OUT}/figures/fig6_noise_sensitivity.png", caption="../report/fig6.rst", category="Figures",
                   subcategory="Noise (Figs. 4-6)",
                   labels=report_pages.labels("Convergence over N; thresholds of FS, CS01, CS02 at each noise level",
                                              "Fig. 6")),
        pdf=f"{OUT}/figures/fig6_noise_sensitivity.pdf",
    log:
        f"{OUT}/logs/figures/fig6_noise_sensitivity.log",
    params:
        expect=report_pages.ExpectedAttributes({**CONVERGENCE,
                **expected(spectrum_files(FIG6_PANELS, LEVELS), spectra_expected(FIG6_PANELS, LEVELS))}),
        plotting=PLOTTING,
        panels=FIG6_PANELS,
        a_max0=config["a_max0"],
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/figure_noise_sensitivity.py"


rule figure_sampling:
    input:
        sweep=SAMPLING_FILES,
        references=spectrum_files(SAMPLING["strategies"], [SAMPLING["noise_level"]]),
    output:
        png=report(f"{OUT}/figures/fig7_sampling.png", caption="../report/fig7.rst", category="Figures",
                   subcategory="Timing (Figs. 7-8)",
                   labels=report_pages.labels("Thresholds of CS01 and CS02 at each sampling time", "Fig. 7")),
        pdf=f"{OUT}/figures/fig7_sampling.pdf",
    log:
        f"{OUT}/logs/figures/fig7_sampling.log",
    params:
        expect=report_pages.ExpectedAttributes({**expected(SAMPLING_FILES, [EXPECT.spectrum(*key) for key in SAMPLING_KEYS]),
                **expected(spectrum_files(SAMPLING["strategies"], [SAMPLING["noise_level"]]),
                           spectra_expected(SAMPLING["strategies"], [SAMPLING["noise_level"]]))}),
        plotting=PLOTTING,
        variable="sampling_time",
        paper_figure="7",
        a_max0=config["a_max0"],
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/figure_timing.py"


rule figure_delay:
    input:
        sweep=DELAY_FILES,
        references=DELAY_REFERENCES,
    output:
        png=report(f"{OUT}/figures/fig8_delay.png", caption="../report/fig8.rst", category="Figures",
                   subcategory="Timing (Figs. 7-8)",
                   labels=report_pages.labels("Thresholds of CS01 and CS02 at each actuation delay", "Fig. 8")),
        pdf=f"{OUT}/figures/fig8_delay.pdf",
    log:
        f"{OUT}/logs/figures/fig8_delay.log",
    params:
        expect=report_pages.ExpectedAttributes({**expected(DELAY_FILES, [EXPECT.spectrum(*key) for key in DELAY_KEYS]),
                **expected(DELAY_REFERENCES, [EXPECT.spectrum(*key) for key in DELAY_REFERENCE_KEYS])}),
        plotting=PLOTTING,
        variable="delay",
        paper_figure="8",
        a_max0=config["a_max0"],
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/figure_timing.py"


rule figure_maps:
    input:
        [f"{OUT}/maps/{s}.nc" for s in config["maps"]["strategies"]],
    output:
        png=report(f"{OUT}/figures/maps_overturning.png", caption="../report/maps.rst", category="Figures",
                   subcategory="Overturning maps",
                   labels=report_pages.labels("Outcome at every frequency and amplitude, noise-free", "§4")),
        pdf=f"{OUT}/figures/maps_overturning.pdf",
    log:
        f"{OUT}/logs/figures/maps_overturning.log",
    params:
        expect=expected([f"{OUT}/maps/{s}.nc" for s in config["maps"]["strategies"]],
                        [EXPECT.map(s) for s in config["maps"]["strategies"]]),
        plotting=PLOTTING,
        strategies=config["maps"]["strategies"],
        a_max0=config["a_max0"],
    conda:
        "../envs/rockstudy.yaml"
    threads: 1
    script:
        "../scripts/figure_maps.py"
