# Design charts beyond the paper's block (docs/records-and-design.md): a block sweep over size R and
# slenderness alpha (J_OS over FS on the noise-free Eq. 23 excitation and the fragility median on a
# record suite, every strategy), and a device sweep over kappa_max and xi for the study's block.
# Target: `snakemake -j2 design` (not in `all`). Every design point is one job. Needs the optional
# `design:` section of the config.

DESIGN = config.get("design")

if DESIGN:
    DBLOCKS = DESIGN["blocks"]
    DDEVICES = DESIGN["devices"]
    DESIGN_BLOCK_KEYS = [(R, a) for R in DBLOCKS["R"] for a in DBLOCKS["alpha"]]
    DESIGN_DEVICE_KEYS = [(k, xi) for k in DDEVICES["kappa_max"] for xi in DDEVICES["damping_ratio"]]
    DESIGN_BLOCK_FILES = [f"{OUT}/design/blocks/R{R:g}_a{a:g}.nc" for R, a in DESIGN_BLOCK_KEYS]
    DESIGN_DEVICE_FILES = [f"{OUT}/design/devices/k{k:g}_xi{xi:g}.nc" for k, xi in DESIGN_DEVICE_KEYS]
    DESIGN_FIGURES = [f"{OUT}/figures/design_{name}.{ext}" for name in ("jos_maps", "winner", "size_effect",
                                                                      "devices") for ext in ("png", "pdf")]

    wildcard_constraints:
        R="[0-9.e-]+",
        alpha="[0-9.e-]+",
        kappa="[0-9.e-]+",
        xi="[0-9.e-]+",

    localrules:
        design,
        design_gather,
        design_figures,

    rule design:
        input:
            f"{OUT}/design/blocks.nc",
            f"{OUT}/design/devices.nc",
            f"{OUT}/tables/design_devices.md",
            DESIGN_FIGURES,

    rule design_block:
        input:
            compiled=ancient(COMPILED),
        output:
            f"{OUT}/design/blocks/R{{R}}_a{{alpha}}.nc",
        log:
            f"{OUT}/logs/design/blocks/R{{R}}_a{{alpha}}.log",
        params:
            design=DESIGN,
            anchorage=config["anchorage"],
            excitation=config["excitation"],
            overturn_criterion=config["overturn_criterion"],
            free_time=config["free_time"],
            library=LIBRARY,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        resources:
            mem_mb=SIM_MEM_MB,
            runtime=10,
        script:
            "../scripts/design_block.py"

    rule design_device:
        input:
            compiled=ancient(COMPILED),
        output:
            f"{OUT}/design/devices/k{{kappa}}_xi{{xi}}.nc",
        log:
            f"{OUT}/logs/design/devices/k{{kappa}}_xi{{xi}}.log",
        params:
            design=DESIGN,
            block=config["block"],
            anchorage=config["anchorage"],
            overturn_criterion=config["overturn_criterion"],
            free_time=config["free_time"],
            library=LIBRARY,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        resources:
            mem_mb=SIM_MEM_MB,
            runtime=10,
        script:
            "../scripts/design_device.py"

    rule design_gather:
        input:
            blocks=DESIGN_BLOCK_FILES,
            devices=DESIGN_DEVICE_FILES,
        output:
            blocks=f"{OUT}/design/blocks.nc",
            devices=f"{OUT}/design/devices.nc",
            md=report(f"{OUT}/tables/design_devices.md", caption="../report/design_devices_table.rst",
                      category="Tables", subcategory="Design charts",
                      labels=report_pages.labels("Device design: fragility median per strategy over κ_max and ξ")),
        log:
            f"{OUT}/logs/design/gather.log",
        params:
            expect=report_pages.ExpectedAttributes({**expected(DESIGN_BLOCK_FILES, [EXPECT.design_block(*key) for key in DESIGN_BLOCK_KEYS]),
                    **expected(DESIGN_DEVICE_FILES, [EXPECT.design_device(*key) for key in DESIGN_DEVICE_KEYS])}),
            target=DDEVICES["target_median_g"],
            block=config["block"],
            library=BOOKKEEPING,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/design_gather.py"

    rule design_figures:
        input:
            blocks=f"{OUT}/design/blocks.nc",
            devices=f"{OUT}/design/devices.nc",
        output:
            jos=report(f"{OUT}/figures/design_jos_maps.png", caption="../report/design_jos_maps.rst",
                       category="Figures", subcategory="Design charts",
                       labels=report_pages.labels("J_OS over FS across block size R and slenderness α")),
            jos_pdf=f"{OUT}/figures/design_jos_maps.pdf",
            winner=report(f"{OUT}/figures/design_winner.png", caption="../report/design_winner.rst",
                          category="Figures", subcategory="Design charts",
                          labels=report_pages.labels("Which strategy wins where over (R, α)")),
            winner_pdf=f"{OUT}/figures/design_winner.pdf",
            size=report(f"{OUT}/figures/design_size_effect.png", caption="../report/design_size_effect.rst",
                        category="Figures", subcategory="Design charts",
                        labels=report_pages.labels("Size effect: fragility median against block size")),
            size_pdf=f"{OUT}/figures/design_size_effect.pdf",
            devices=report(f"{OUT}/figures/design_devices.png", caption="../report/design_devices.rst",
                           category="Figures", subcategory="Design charts",
                           labels=report_pages.labels("Fragility median over the device's κ_max and ξ")),
            devices_pdf=f"{OUT}/figures/design_devices.pdf",
        log:
            f"{OUT}/logs/figures/design.log",
        params:
            expect=expected([f"{OUT}/design/blocks.nc", f"{OUT}/design/devices.nc"],
                            [EXPECT.design_blocks(), EXPECT.design_devices()]),
            target=DDEVICES["target_median_g"],
            plotting=PLOTTING,
        conda:
            "../envs/rockstudy.yaml"
        threads: 1
        script:
            "../scripts/design_figures.py"
