rule notebook:
    """Execute a jupytext notebook (percent format) and render it to HTML."""
    input:
        notebook="notebooks/{name}.py",
        results=notebook_inputs,
    output:
        html=report("results/notebooks/{name}.html", caption="../report/notebook.rst", category="Notebooks"),
    wildcard_constraints:
        name="|".join(NOTEBOOKS),
    params:
        code=notebook_code,
    benchmark:
        "results/benchmarks/notebook/notebook/{name}.tsv",
    log:
        "logs/notebooks/{name}.log",
    conda:
        ENV
    script:
        "../scripts/notebook.py"
