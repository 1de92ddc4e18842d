"""Snakemake script: the README's runtime block (see rule readme_runtime)."""
from sphereimpact.study.readme import write_runtime
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "README runtime block"):
    write_runtime(snakemake.params.root, snakemake.output.md)
