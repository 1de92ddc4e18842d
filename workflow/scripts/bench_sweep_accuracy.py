"""Snakemake script: the sweep benchmark's untimed half (see rule bench_sweep_accuracy)."""
from sphereimpact.study.numerics import write_bench_sweep_accuracy
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "sweep benchmark accuracy"):
    write_bench_sweep_accuracy(snakemake.params.config, snakemake.output.json)
