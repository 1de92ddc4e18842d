"""Snakemake script: write the summary table (see rule tabulate)."""
from sphereimpact.study.tables import write_summary
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], f"tabulate {len(snakemake.input.runs)} runs"):
    write_summary(snakemake.input.runs, snakemake.output.csv, snakemake.output.md)
