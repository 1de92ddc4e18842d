rule figure:
    """One chapter figure (Figs 4.2-4.8) from the run files; never re-simulates."""
    input:
        runs=figure_runs,
        published=PUBLISHED,
        code=code("workflow/scripts/figure.py"),
    output:
        png=report("paper_figures/{fig}.png", caption="../report/chapter_figure.rst", category="Chapter figures"),
        pdf="paper_figures/{fig}.pdf",
    params:
        config=params_for("figure"),
    wildcard_constraints:
        fig="fig4_[2-8]",
    log:
        "logs/figures/{fig}.log",
    conda:
        ENV
    script:
        "../scripts/figure.py"
