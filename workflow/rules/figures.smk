rule figure:
    """One chapter figure (Figs 4.2-4.8) from the run files; never re-simulates."""
    input:
        runs=figure_runs,
        published=PUBLISHED,
    output:
        png=report("paper_figures/{fig}.png", caption="../report/figure.rst", category="Chapter figures"),
        pdf="paper_figures/{fig}.pdf",
    params:
        code=code("workflow/scripts/figure.py"),
        config=params_for("figure"),
        captions=lambda wildcards: captions(wildcards.fig),
    wildcard_constraints:
        fig="fig4_[2-8]",
    benchmark:
        "results/benchmarks/figures/figure/{fig}.tsv",
    log:
        "logs/figures/{fig}.log",
    conda:
        ENV
    script:
        "../scripts/figure.py"


rule figure_index:
    """paper_figures/README.md: every figure with its caption (the folder's index a reader sees), the chapter
    figures' facts read from their run files."""
    input:
        runs=sorted({run for fig in drawable_figures() for run in chapter_runs(fig)}),
    output:
        md="paper_figures/README.md",
    params:
        code=code("workflow/scripts/figure_index.py"),
        config=params_for("figure_index"),
        runs={fig: chapter_runs(fig) for fig in drawable_figures()},
    benchmark:
        "results/benchmarks/figures/figure_index.tsv",
    log:
        "logs/figures/index.log",
    conda:
        ENV
    script:
        "../scripts/figure_index.py"
