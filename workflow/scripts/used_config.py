"""Snakemake script: write the configuration this run used (see rule used_config)."""
from sphereimpact.study.config import write_config
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "write the configuration used"):
    write_config(snakemake.params.config, snakemake.output.yaml)
