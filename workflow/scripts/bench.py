"""Snakemake script: simulate against the hand-written script (see rule bench)."""
from sphereimpact.study.numerics import write_bench
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "bench"):
    write_bench(snakemake.params.config, snakemake.output.csv, snakemake.output.stages, snakemake.output.profile,
                snakemake.input.get("kernels") or None)
