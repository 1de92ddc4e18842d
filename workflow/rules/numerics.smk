# Accuracy against speed: work-precision, where methods fail, model ablation (timings vary run to run).


rule work_precision:
    """Every solve_ivp method x body x tolerance (plus the closed form) against reference solutions."""
    output:
        csv="results/work_precision.csv",
    params:
        config=config,
    threads: workflow.cores  # timed: no other job shares the machine
    log:
        "logs/work_precision.log",
    conda:
        ENV
    script:
        "../scripts/numerics.py"


rule bench:
    """Speed-up of the reduced model over the planar one, and of the closed form, at equal accuracy."""
    input:
        csv="results/work_precision.csv",
    output:
        csv="results/bench.csv",
    threads: workflow.cores  # timed: no other job shares the machine
    log:
        "logs/bench.log",
    conda:
        ENV
    script:
        "../scripts/bench.py"


rule stability:
    """Five failure modes measured for every method beside the package's default path."""
    output:
        csv="results/stability.csv",
    params:
        config=config_for_case(CASES[0]),
    log:
        "logs/stability.log",
    conda:
        ENV
    script:
        "../scripts/numerics.py"


rule ablation:
    """Change in every output when the model adds or drops one thing."""
    input:
        published=PUBLISHED,
    output:
        csv="results/ablation.csv",
    params:
        config=config,
    log:
        "logs/ablation.log",
    conda:
        ENV
    script:
        "../scripts/numerics.py"


rule numerics_figure:
    """Work-precision and stability charts from their CSV files."""
    input:
        csv="results/{study}.csv",
    output:
        png="paper_figures/{study}.png",
    wildcard_constraints:
        study="work_precision|stability",
    log:
        "logs/figures/{study}.log",
    conda:
        ENV
    script:
        "../scripts/numerics_figure.py"
