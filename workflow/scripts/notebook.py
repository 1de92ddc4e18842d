"""Snakemake script: execute a jupytext notebook to HTML (see rule notebook)."""
from sphereimpact.study.notebook import execute_to_html
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], f"execute {snakemake.input.notebook}"):
    execute_to_html(snakemake.input.notebook, snakemake.output.html, cwd=".")
