"""Snakemake script: concatenate the sweep shards (see rule sweep_merge)."""
from sphereimpact.study.sweeps import merge
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], f"merge {len(snakemake.input.shards)} shards"):
    merge(snakemake.input.shards, snakemake.output.csv)
