rule notebook:
    """Execute a jupytext notebook (percent format) and render it to HTML."""
    input:
        notebook="notebooks/{name}.py",
        tables=["results/summary.csv", "results/replication.csv"],
        figures=figure_outputs(),
    output:
        html="results/notebooks/{name}.html",
    wildcard_constraints:
        name="replication",
    log:
        "logs/notebooks/{name}.log",
    conda:
        ENV
    script:
        "../scripts/notebook.py"
