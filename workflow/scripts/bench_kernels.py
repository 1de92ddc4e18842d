"""Snakemake script: the compiled kernels' compilation and load (see rule bench_kernels)."""
from sphereimpact.study.numerics import write_kernel_bench
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "kernels' compilation"):
    write_kernel_bench(snakemake.params.config, snakemake.output.csv)
