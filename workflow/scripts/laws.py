"""Snakemake script: the contact laws fitted to one COR and contact time, swept in speed (see rule laws)."""
from sphereimpact.study.laws import write_laws
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "contact laws"):
    write_laws(snakemake.params.config, snakemake.output.fitted, snakemake.output.speed, snakemake.output.force)
