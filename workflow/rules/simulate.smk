rule simulate:
    """One impact per case x force model, under every configured separation criterion."""
    output:
        csv="results/runs/{case}_{model}.csv",
        json="results/runs/{case}_{model}.json",
    params:
        config=lambda wildcards: config_for_case(wildcards.case),
    wildcard_constraints:
        case="[A-Za-z][A-Za-z0-9]*",
        model="[a-z-]+",
    log:
        "logs/simulate/{case}_{model}.log",
    conda:
        ENV
    script:
        "../scripts/simulate.py"
