rule figure:
    """One chapter figure (Figs 4.2-4.8) from the run files; never re-simulates."""
    input:
        runs=figure_runs,
        published=PUBLISHED,
    output:
        png="paper_figures/{fig}.png",
        pdf="paper_figures/{fig}.pdf",
    params:
        separation=config["figure_separation"],
    wildcard_constraints:
        fig="fig4_[2-8]",
    log:
        "logs/figures/{fig}.log",
    conda:
        ENV
    script:
        "../scripts/figure.py"
