"""Snakemake script: the contact-law figures (see rule laws_figures)."""
from sphereimpact.figures.laws import cor_speed, force_deflection
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "contact-law figures"):
    cor_speed(snakemake.input.speed, snakemake.input.fitted, [snakemake.output.cor_speed])
    force_deflection(snakemake.input.force, [snakemake.output.force])
