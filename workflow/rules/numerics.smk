# Accuracy against speed: work-precision, where methods fail, model ablation (timings vary run to run).


rule numerics_references:
    """The reference solutions of the timed studies (work-precision, stiffness), computed beside other jobs so that
    the timed ones, which run alone, spend their time timing."""
    output:
        json="results/numerics/references.json",
    params:
        code=code("workflow/scripts/numerics_references.py"),
        config=params_for("numerics_references"),
    priority: 1  # early: two timed jobs wait for it
    benchmark:
        "results/benchmarks/numerics/numerics_references.tsv"
    log:
        "logs/numerics_references.log",
    conda:
        ENV
    script:
        "../scripts/numerics_references.py"


rule bench_kernels:
    """The compiled kernels' compilation on a fresh machine and their load from the disk cache, rows the bench table
    takes in: fresh processes of one core each, so the job runs beside others (the timed jobs, which run alone,
    spend their time on timings that share nothing)."""
    output:
        csv="results/numerics/kernels.csv",
    params:
        code=code("workflow/scripts/bench_kernels.py"),
        config=params_for("bench_kernels"),
    priority: 1  # early: the timed bench waits for it
    benchmark:
        "results/benchmarks/numerics/bench_kernels.tsv"
    log:
        "logs/bench_kernels.log",
    conda:
        ENV
    script:
        "../scripts/bench_kernels.py"


rule work_precision:
    """Every solve_ivp method x body x tolerance (plus the closed form) against reference solutions."""
    input:
        references="results/numerics/references.json",
    output:
        csv=report("results/work_precision.csv", caption="../report/work_precision.rst", category="Numerics"),
    params:
        code=code("workflow/scripts/numerics.py"),
        config=params_for("work_precision"),
    threads: workflow.cores  # timed: no other job shares the machine
    benchmark:
        "results/benchmarks/numerics/work_precision.tsv",
    log:
        "logs/work_precision.log",
    conda:
        ENV
    script:
        "../scripts/numerics.py"


rule bench:
    """simulate against a hand-written solve_ivp script, and the reduced model against the planar one."""
    input:
        kernels=lambda wildcards: "results/numerics/kernels.csv" if config["bench"]["kernels"] else [],
    output:
        csv=report("results/bench.csv", caption="../report/bench.rst", category="Numerics"),
        stages=report("results/bench_stages.csv", caption="../report/bench_stages.rst", category="Numerics"),
        profile=report("results/bench_profile.csv", caption="../report/bench_profile.rst", category="Numerics"),
    params:
        code=code("workflow/scripts/bench.py"),
        config=params_for("bench"),
    threads: workflow.cores  # timed: no other job shares the machine
    benchmark:
        "results/benchmarks/numerics/bench.tsv",
    log:
        "logs/bench.log",
    conda:
        ENV
    script:
        "../scripts/bench.py"


rule stability_study:
    """One failure mode measured for every method beside the package's default path; the stiffness study, whose
    times the table reports, runs alone, on references computed before it."""
    input:
        references=lambda wildcards: "results/numerics/references.json" if wildcards.study == "stiffness" else [],
    output:
        csv=temp("results/stability/{study}.csv"),
    params:
        code=code("workflow/scripts/stability.py"),
        config=params_for("stability", CASES[0]),
    wildcard_constraints:
        study="[a-z-]+",
    threads: lambda wildcards: workflow.cores if wildcards.study == "stiffness" else 1  # timed: alone
    benchmark:
        "results/benchmarks/numerics/stability_study/{study}.tsv"
    log:
        "logs/stability/{study}.log",
    conda:
        ENV
    script:
        "../scripts/stability.py"


rule stability:
    """Five failure modes measured for every method beside the package's default path: the studies' tables as
    one, in the config's order."""
    input:
        parts=expand("results/stability/{study}.csv", study=config["numerics"]["stability"]),
    output:
        csv=report("results/stability.csv", caption="../report/stability.rst", category="Numerics"),
    params:
        code=code("workflow/scripts/stability_merge.py"),
    benchmark:
        "results/benchmarks/numerics/stability.tsv"
    log:
        "logs/stability.log",
    conda:
        ENV
    script:
        "../scripts/stability_merge.py"


rule ablation:
    """Change in every output when the model adds or drops one thing."""
    input:
        published=PUBLISHED,
    output:
        csv=report("results/ablation.csv", caption="../report/ablation.rst", category="Numerics"),
    params:
        code=code("workflow/scripts/numerics.py"),
        config=params_for("ablation"),
    benchmark:
        "results/benchmarks/numerics/ablation.tsv",
    log:
        "logs/ablation.log",
    conda:
        ENV
    script:
        "../scripts/numerics.py"


rule microslip_resolution:
    """The microslip contact's accuracy against cost over cells x time steps; the default it supports."""
    output:
        csv=report("results/microslip_resolution.csv", caption="../report/microslip_resolution.rst",
                   category="Numerics"),
    params:
        code=code("workflow/scripts/numerics.py"),
        config=params_for("microslip_resolution"),
    threads: workflow.cores  # timed: no other job shares the machine
    benchmark:
        "results/benchmarks/numerics/microslip_resolution.tsv",
    log:
        "logs/microslip_resolution.log",
    conda:
        ENV
    script:
        "../scripts/numerics.py"


rule numerics_figure:
    """The chart of a numerical study from its CSV file: the stability chart, which holds no timing, beside the
    chapter's committed figures (a changed one fails `.ci/run`)."""
    input:
        csv="results/{study}.csv",
    output:
        png=report("paper_figures/{study}.png", caption="../report/figure.rst", category="Numerics"),
    wildcard_constraints:
        study="stability",
    params:
        code=code("workflow/scripts/numerics_figure.py"),
        captions=lambda wildcards: captions(wildcards.study),
    benchmark:
        "results/benchmarks/numerics/numerics_figure/{study}.tsv",
    log:
        "logs/figures/{study}.log",
    conda:
        ENV
    script:
        "../scripts/numerics_figure.py"


use rule numerics_figure as timing_chart with:
    """A chart of timings (work-precision, microslip resolution, sweep paths): each run's own, under results/;
    `python -m sphereimpact.study.readme --update` copies the run the README's speed tables come from into
    paper_figures/."""
    output:
        png=report("results/figures/{study}.png", caption="../report/figure.rst", category="Numerics"),
    wildcard_constraints:
        study="|".join(TIMING_CHARTS),
    benchmark:
        "results/benchmarks/numerics/timing_chart/{study}.tsv"
    log:
        "logs/figures/{study}.log",
