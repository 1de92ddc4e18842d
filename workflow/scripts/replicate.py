"""Snakemake script: write the published-value report (see rule replicate)."""
from sphereimpact.study.replication import write_report
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], f"compare with {snakemake.input.published}"):
    write_report(snakemake.params.config, snakemake.input.published, snakemake.input.runs,
                 snakemake.output.csv, snakemake.output.md, snakemake.output.findings)
