"""Snakemake script: compliant against rigid tangential contact for the chapter's ball (see rule compliance_map)."""
from sphereimpact.study.validation import write_compliance_map
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "compliance map"):
    write_compliance_map(snakemake.params.config, snakemake.output.csv)
