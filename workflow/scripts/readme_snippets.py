"""Snakemake script: the README's generated blocks (see rule readme_snippets)."""
from sphereimpact.study.readme import write_snippets
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "README snippets"):
    write_snippets(snakemake.params.config, snakemake.input.replication, snakemake.input.findings, snakemake.input.bench,
                   snakemake.input.bench_sweep, snakemake.output.replication, snakemake.output.speed)
