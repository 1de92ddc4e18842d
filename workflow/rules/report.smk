rule tabulate:
    """Summary table: one row per case x force model x separation criterion."""
    input:
        runs=run_files("json"),
    output:
        csv=report("results/summary.csv", caption="../report/summary.rst", category="Replication"),
        md="results/summary.md",
    params:
        code=code("workflow/scripts/tabulate.py"),
    benchmark:
        "results/benchmarks/report/tabulate.tsv",
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
        csv=report("results/replication.csv", caption="../report/replication.rst", category="Replication"),
        md=report("results/replication.md", caption="../report/replication_md.rst", category="Replication"),
        findings="results/replication_findings.md",
    params:
        code=code("workflow/scripts/replicate.py"),
        config=params_for("replicate"),
    benchmark:
        "results/benchmarks/report/replicate.tsv",
    log:
        "logs/replicate.log",
    conda:
        ENV
    script:
        "../scripts/replicate.py"


rule readme_snippets:
    """The README's generated blocks (replication, speed and validation tables, the sweep's differential test),
    from the result files."""
    input:
        replication="results/replication.csv",
        findings="results/replication_findings.md",
        bench="results/bench.csv",
        bench_sweep="results/bench_sweep.csv",
        validation_summary="results/validation_summary.csv",
        validation="results/validation.csv",
        consistency="results/consistency.csv",
        fit="results/fit_kharaz/fit.json",
    output:
        replication="results/readme/replication.md",
        speed="results/readme/speed.md",
        validation="results/readme/validation.md",
        consistency="results/readme/consistency.md",
        fit="results/readme/fit.md",
    params:
        code=code("workflow/scripts/readme_snippets.py"),
        config=params_for("readme"),
    benchmark:
        "results/benchmarks/report/readme_snippets.tsv",
    log:
        "logs/readme_snippets.log",
    conda:
        ENV
    script:
        "../scripts/readme_snippets.py"


rule readme_runtime:
    """The README's block of what the pipeline's jobs took, from their benchmark files: it runs after every
    other job of the replication."""
    input:
        chapter_outputs(),
    output:
        md="results/readme/runtime.md",
    params:
        code=code("workflow/scripts/readme_runtime.py"),
        root="results/benchmarks",
    log:
        "logs/readme_runtime.log",
    conda:
        ENV
    script:
        "../scripts/readme_runtime.py"


rule used_config:
    """The configuration this run used (validated, defaults filled in), for the notebooks to read."""
    output:
        yaml=report("results/config.yaml", caption="../report/used_config.rst", category="Replication"),
    params:
        code=code("workflow/scripts/used_config.py"),
        config=config,
    benchmark:
        "results/benchmarks/report/used_config.tsv",
    log:
        "logs/used_config.log",
    conda:
        ENV
    script:
        "../scripts/used_config.py"
