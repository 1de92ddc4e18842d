"""Snakemake script: the sweep benchmark (see rule bench_sweep)."""
from sphereimpact.study.numerics import write_bench_sweep
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "sweep benchmark"):
    write_bench_sweep(snakemake.params.config, snakemake.output.csv, snakemake.input.data, snakemake.input.accuracy)
