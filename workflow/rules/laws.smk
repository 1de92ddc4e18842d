# Contact laws: each calibrated to one COR and contact time on the configured ball, swept in speed; the
# published COR relations measured against exact calibration.


rule laws:
    """Fit every law in laws.models, then COR, contact time and peak force against speed, and force curves."""
    output:
        fitted=report("results/laws_fitted.csv", caption="../report/laws.rst", category="Contact laws"),
        speed=report("results/laws.csv", caption="../report/laws.rst", category="Contact laws"),
        force="results/laws_force.csv",
    params:
        code=code("workflow/scripts/laws.py"),
        config=params_for("laws"),
    benchmark:
        "results/benchmarks/laws/laws.tsv",
    log:
        "logs/laws/laws.log",
    conda:
        ENV
    script:
        "../scripts/laws.py"


rule cor_relations:
    """The COR each published relation gives against the COR it was asked for, beside exact calibration."""
    output:
        csv=report("results/cor_relations.csv", caption="../report/laws.rst", category="Contact laws"),
    params:
        code=code("workflow/scripts/cor_relations.py"),
        config=params_for("cor_relations"),
    benchmark:
        "results/benchmarks/laws/cor_relations.tsv",
    log:
        "logs/laws/cor_relations.log",
    conda:
        ENV
    script:
        "../scripts/cor_relations.py"


rule laws_figures:
    """COR, contact time and peak force against speed; force against deflection."""
    input:
        fitted="results/laws_fitted.csv",
        speed="results/laws.csv",
        force="results/laws_force.csv",
    output:
        cor_speed=report("paper_figures/laws_cor_speed.png", caption="../report/figure.rst", category="Contact laws"),
        force=report("paper_figures/laws_force.png", caption="../report/figure.rst", category="Contact laws"),
    params:
        code=code("workflow/scripts/laws_figures.py"),
        captions=captions("laws_cor_speed", "laws_force"),
    benchmark:
        "results/benchmarks/laws/laws_figures.tsv",
    log:
        "logs/laws/figures.log",
    conda:
        ENV
    script:
        "../scripts/laws_figures.py"
