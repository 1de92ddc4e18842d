# Against real measurements: the rigid and the compliant tangential contact on Kharaz, Gorham & Salman
# (2001); where compliance matters for the chapter's ball.


rule validation:
    """Each measured point against each tangential model; model curves; Maw's variables of the data."""
    input:
        data=config["validation"]["data"],
    output:
        residuals=report("results/validation.csv", caption="../report/validation.rst", category="Validation"),
        summary=report("results/validation_summary.csv", caption="../report/validation.rst", category="Validation"),
        curves="results/validation_curves.csv",
        maw="results/validation_maw.csv",
    params:
        code=code("workflow/scripts/validation.py"),
        config=params_for("validation"),
    benchmark:
        "results/benchmarks/validation/validation.tsv",
    log:
        "logs/validation/validation.log",
    conda:
        ENV
    script:
        "../scripts/validation.py"


rule kharaz_fit:
    """The free parameters (mu, kappa) fitted to the Kharaz data, e_n given, with their standard errors."""
    input:
        data=config["validation"]["data"],
    output:
        ball="results/fit_kharaz/ball.json",
        summary=report("results/fit_kharaz/fit.json", caption="../report/validation.rst", category="Validation"),
        residuals="results/fit_kharaz/residuals.csv",
        png=report("results/fit_kharaz/fit.png", caption="../report/validation.rst", category="Validation"),
    params:
        code=code("workflow/scripts/kharaz_fit.py"),
        config=params_for("kharaz_fit"),
    benchmark:
        "results/benchmarks/validation/kharaz_fit.tsv",
    log:
        "logs/validation/kharaz_fit.log",
    conda:
        ENV
    script:
        "../scripts/kharaz_fit.py"


rule compliance_map:
    """The chapter's ball over angle x kappa: where the rigid tangential contact is enough."""
    output:
        csv=report("results/compliance_map.csv", caption="../report/validation.rst", category="Validation"),
    params:
        code=code("workflow/scripts/compliance_map.py"),
        config=params_for("compliance_map"),
    benchmark:
        "results/benchmarks/validation/compliance_map.tsv",
    log:
        "logs/validation/compliance_map.log",
    conda:
        ENV
    script:
        "../scripts/compliance_map.py"


rule validation_figures:
    """The model against the data (physical and Maw's variables) and the chapter-ball map."""
    input:
        data=config["validation"]["data"],
        curves="results/validation_curves.csv",
        summary="results/validation_summary.csv",
        maw="results/validation_maw.csv",
        map="results/compliance_map.csv",
    output:
        kharaz=report("paper_figures/validation_kharaz.png", caption="../report/figure.rst", category="Validation"),
        maw=report("paper_figures/validation_maw.png", caption="../report/figure.rst", category="Validation"),
        map=report("paper_figures/compliance_map.png", caption="../report/figure.rst", category="Validation"),
    params:
        code=code("workflow/scripts/validation_figures.py"),
        captions=captions("validation_kharaz", "validation_maw", "compliance_map"),
        config=params_for("validation_figures"),
    benchmark:
        "results/benchmarks/validation/validation_figures.tsv",
    log:
        "logs/validation/figures.log",
    conda:
        ENV
    script:
        "../scripts/validation_figures.py"


rule planning:
    """Which bounces to measure (sphereimpact plan): the Kharaz ball's best incidences against the measured ones,
    the predicted errors checked by fits of synthetic bounces, and the README's tennis example."""
    input:
        data=config["validation"]["data"],
        schema="config/schema.yaml",
        study=config["planning"]["tennis"]["study"],
        candidates=config["planning"]["tennis"]["candidates"],
    output:
        kharaz=[f"results/plan/kharaz/{name}" for name in PLAN_FILES],
        figure=report("paper_figures/plan_kharaz.png", caption="../report/figure.rst", category="Validation"),
        checks=report("results/plan/checks.csv", caption="../report/planning.rst", category="Validation"),
        tennis=[f"results/plan/tennis/{name}" for name in PLAN_FILES],
        plan_md="results/readme/plan.md",
        checks_md="results/readme/plan_checks.md",
    params:
        code=code("workflow/scripts/planning.py"),
        config=params_for("planning"),
        captions=captions("plan_kharaz"),
    benchmark:
        "results/benchmarks/validation/planning.tsv"
    log:
        "logs/validation/planning.log",
    conda:
        ENV
    script:
        "../scripts/planning.py"
