"""Snakemake script: what COR each published relation really gives (see rule cor_relations)."""
from sphereimpact.study.laws import write_relations
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "COR relations"):
    write_relations(snakemake.params.config, snakemake.output.csv)
