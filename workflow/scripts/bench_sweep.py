"""Snakemake script: the sweep benchmark (see rule bench_sweep)."""
from sphereimpact.study.workflow import job_log
from sphereimpact.numerics.bench_sweep import run

with job_log(snakemake.log[0], "sweep benchmark"):
    run(snakemake.output.csv, **snakemake.params.config["bench"])
