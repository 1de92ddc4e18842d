# Sweeps: a sharded angle x speed table of the configured ball, a speed table, maps and a benchmark.

SHARDS = list(range(config["sweep"]["shards"]))


rule sweep_shard:
    """One contiguous block of the angle x speed sweep (interpolants span the whole sweep)."""
    output:
        csv="results/sweep/shards/angle_speed_{shard}.csv",
    params:
        config=config,
        shard=lambda wildcards: int(wildcards.shard),
        shards=len(SHARDS),
    wildcard_constraints:
        shard="[0-9]+",
    resources:
        mem_mb=4000,
        runtime=30,
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
        csv="results/sweep/angle_speed.csv",
    log:
        "logs/sweep/merge.log",
    conda:
        ENV
    script:
        "../scripts/sweep_merge.py"


rule speed_table:
    """Normal impact against speed, both force laws: COR, contact time, peak force."""
    output:
        csv="results/sweep/speed.csv",
    params:
        config=config,
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
    output:
        png="paper_figures/{map}.png",
    params:
        map_speed=config["sweep"]["map_speed"],
    wildcard_constraints:
        map="spin_map|cor_speed|contact_speed",
    log:
        "logs/figures/{map}.log",
    conda:
        ENV
    script:
        "../scripts/sweep_map.py"


rule bench_sweep:
    """Throughput of the sweep engine against per-scene solving at equal accuracy (a benchmark)."""
    output:
        csv="results/bench_sweep.csv",
    threads: workflow.cores  # timed: no other job shares the machine
    log:
        "logs/bench_sweep.log",
    conda:
        ENV
    script:
        "../scripts/bench_sweep.py"
