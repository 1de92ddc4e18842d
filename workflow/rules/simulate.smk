rule simulate:
    """One impact per case x force model, under every configured separation criterion."""
    output:
        csv=report(
            "results/runs/{case}_{model}.csv",
            caption="../report/run.rst",
            category="Runs",
            labels={"case": "{case}", "model": "{model}"},
        ),
        json="results/runs/{case}_{model}.json",
    params:
        code=code("workflow/scripts/simulate.py"),
        config=lambda wildcards: params_for("simulate", wildcards.case),
    wildcard_constraints:
        case="[A-Za-z][A-Za-z0-9]*",
        model="[a-z-]+",
    benchmark:
        "results/benchmarks/simulate/simulate/{case}_{model}.tsv",
    log:
        "logs/simulate/{case}_{model}.log",
    conda:
        ENV
    script:
        "../scripts/simulate.py"
