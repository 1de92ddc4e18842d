rule tabulate:
    """Summary table: one row per case x force model x separation criterion."""
    input:
        runs=run_files("json"),
    output:
        csv="results/summary.csv",
        md="results/summary.md",
    log:
        "logs/tabulate.log",
    conda:
        ENV
    script:
        "../scripts/tabulate.py"


rule replicate:
    """Every printed value: published, reproduced, status, and the hypotheses that explain a difference."""
    input:
        runs=run_files("json"),
        published=PUBLISHED,
    output:
        csv="results/replication.csv",
        md="results/replication.md",
    params:
        config=config,
    log:
        "logs/replicate.log",
    conda:
        ENV
    script:
        "../scripts/replicate.py"
