rule notebook:
    """Execute a jupytext notebook (percent format) and render it to HTML."""
    input:
        notebook="notebooks/{name}.py",
        results=notebook_inputs,
    output:
        html="results/notebooks/{name}.html",
    wildcard_constraints:
        name="|".join(NOTEBOOKS),
    log:
        "logs/notebooks/{name}.log",
    conda:
        ENV
    script:
        "../scripts/notebook.py"
