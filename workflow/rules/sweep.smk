# Sweeps: a sharded angle x speed table of the configured ball, a speed table, maps and a benchmark.

SHARDS = list(range(config["sweep"]["shards"]))


rule sweep_shard:
    """One contiguous block of the angle x speed sweep (interpolants span the whole sweep)."""
    output:
        csv=temp("results/sweep/shards/angle_speed_{shard}.csv"),
    params:
        code=code("workflow/scripts/sweep_shard.py"),
        config=params_for("sweep_shard"),
        shard=lambda wildcards: int(wildcards.shard),
        shards=len(SHARDS),
    wildcard_constraints:
        shard="[0-9]+",
    resources:
        mem_mb=4000,
        runtime=30,
    benchmark:
        "results/benchmarks/sweep/sweep_shard/{shard}.tsv",
    log:
        "logs/sweep/shard_{shard}.log",
    conda:
        ENV
    script:
        "../scripts/sweep_shard.py"


rule sweep_merge:
    """The shards, concatenated in order: the same table as the sweep run in one piece."""
    input:
        shards=expand("results/sweep/shards/angle_speed_{shard}.csv", shard=SHARDS),
    output:
        csv=report("results/sweep/angle_speed.csv", caption="../report/angle_speed.rst", category="Sweeps"),
    params:
        code=code("workflow/scripts/sweep_merge.py"),
    benchmark:
        "results/benchmarks/sweep/sweep_merge.tsv",
    log:
        "logs/sweep/merge.log",
    conda:
        ENV
    script:
        "../scripts/sweep_merge.py"


rule speed_table:
    """Normal impact against speed, both force laws: COR, contact time, peak force."""
    output:
        csv=report("results/sweep/speed.csv", caption="../report/speed.rst", category="Sweeps"),
    params:
        code=code("workflow/scripts/speed_table.py"),
        config=params_for("speed_table"),
    benchmark:
        "results/benchmarks/sweep/speed_table.tsv",
    log:
        "logs/sweep/speed.log",
    conda:
        ENV
    script:
        "../scripts/speed_table.py"


rule sweep_map:
    """Spin map, COR against speed, contact time and peak force against speed."""
    input:
        angle_speed="results/sweep/angle_speed.csv",
        speed="results/sweep/speed.csv",
        published=PUBLISHED,
        compliance="results/compliance_map.csv",
    output:
        png=report("paper_figures/{map}.png", caption="../report/figure.rst", category="Sweeps"),
    params:
        code=code("workflow/scripts/sweep_map.py"),
        captions=lambda wildcards: captions(wildcards.map),
        config=params_for("sweep_map"),
    wildcard_constraints:
        map="spin_map|cor_speed|contact_speed",
    benchmark:
        "results/benchmarks/sweep/sweep_map/{map}.tsv",
    log:
        "logs/figures/{map}.log",
    conda:
        ENV
    script:
        "../scripts/sweep_map.py"


rule sweep_paths_accuracy:
    """The sweep-path study's untimed half: each contender's error on a sample against the reference."""
    output:
        json="results/sweep/sweep_paths_accuracy.json",
    params:
        code=code("workflow/scripts/sweep_paths_accuracy.py"),
        config=params_for("sweep_paths_accuracy"),
    benchmark:
        "results/benchmarks/sweep/sweep_paths_accuracy.tsv",
    log:
        "logs/sweep_paths_accuracy.log",
    conda:
        ENV
    script:
        "../scripts/sweep_paths_accuracy.py"


rule sweep_paths:
    """The sweep paths that can solve the same scenes, timed against each other at equal target (a benchmark)."""
    input:
        accuracy="results/sweep/sweep_paths_accuracy.json",
    output:
        csv=report("results/sweep_paths.csv", caption="../report/sweep_paths.rst", category="Sweeps"),
    params:
        code=code("workflow/scripts/sweep_paths.py"),
        config=params_for("sweep_paths"),
    threads: workflow.cores  # timed: no other job shares the machine
    benchmark:
        "results/benchmarks/sweep/sweep_paths.tsv",
    log:
        "logs/sweep_paths.log",
    conda:
        ENV
    script:
        "../scripts/sweep_paths.py"


rule bench_sweep_accuracy:
    """The sweep benchmark's untimed half: each sweep's error on a sample, and its contenders' tolerances at it."""
    output:
        json="results/sweep/bench_sweep_accuracy.json",
    params:
        code=code("workflow/scripts/bench_sweep_accuracy.py"),
        config=params_for("bench_sweep_accuracy"),
    benchmark:
        "results/benchmarks/sweep/bench_sweep_accuracy.tsv",
    log:
        "logs/bench_sweep_accuracy.log",
    conda:
        ENV
    script:
        "../scripts/bench_sweep_accuracy.py"


rule bench_sweep:
    """Throughput of the sweep engine against per-scene solving at equal accuracy, and fits (a benchmark)."""
    input:
        data=config["validation"]["data"],
        accuracy="results/sweep/bench_sweep_accuracy.json",
    output:
        csv=report("results/bench_sweep.csv", caption="../report/bench_sweep.rst", category="Sweeps"),
    params:
        code=code("workflow/scripts/bench_sweep.py"),
        config=params_for("bench_sweep"),
    threads: workflow.cores  # timed: no other job shares the machine
    benchmark:
        "results/benchmarks/sweep/bench_sweep.tsv",
    log:
        "logs/bench_sweep.log",
    conda:
        ENV
    script:
        "../scripts/bench_sweep.py"


CONSISTENCY_SHARDS = list(range(config["consistency"]["shards"]))


rule consistency_references:
    """simulate of one block of the differential test's random scenes: each row's reference."""
    output:
        parquet=temp("results/consistency/references_{shard}.parquet"),
    params:
        code=code("workflow/scripts/consistency_references.py"),
        config=params_for("consistency"),
        shard=lambda wildcards: int(wildcards.shard),
        shards=len(CONSISTENCY_SHARDS),
    wildcard_constraints:
        shard="[0-9]+",
    priority: 1  # first: the differential test's chain is the longest of one-core jobs (see rule consistency)
    benchmark:
        "results/benchmarks/sweep/consistency_references/{shard}.tsv",
    log:
        "logs/consistency/references_{shard}.log",
    conda:
        ENV
    script:
        "../scripts/consistency_references.py"


rule consistency:
    """The differential test: the random scenes in one table, swept, every row against its reference."""
    input:
        references=expand("results/consistency/references_{shard}.parquet", shard=CONSISTENCY_SHARDS),
    output:
        csv=report("results/consistency.csv", caption="../report/consistency.rst", category="Sweeps"),
    params:
        code=code("workflow/scripts/consistency.py"),
        config=params_for("consistency"),
    # started as soon as its references are: a long one-core job, it then shares the machine with the short ones,
    # not with an idle core while the timed jobs (which run alone) wait for it
    priority: 1
    benchmark:
        "results/benchmarks/sweep/consistency.tsv",
    log:
        "logs/consistency/consistency.log",
    conda:
        ENV
    script:
        "../scripts/consistency.py"
