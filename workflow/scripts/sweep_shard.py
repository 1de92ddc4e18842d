"""Snakemake script: one shard of the angle x speed sweep (see rule sweep_shard)."""
from sphereimpact.study.sweeps import write_shard
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], f"shard {snakemake.params.shard} of {snakemake.params.shards}"):
    write_shard(snakemake.params.config, snakemake.params.shard, snakemake.params.shards, snakemake.output.csv)
