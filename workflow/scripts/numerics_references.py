"""Snakemake script: the timed numerical studies' reference solutions (see rule numerics_references)."""
from sphereimpact.study.numerics import write_numerics_references
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "reference solutions of the timed studies"):
    write_numerics_references(snakemake.params.config, snakemake.output.json)
