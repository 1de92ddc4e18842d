"""Snakemake script: one bounce's history figure (see rule own_bounce_figure)."""
from sphereimpact.figures.own import bounce_figure
from sphereimpact.study.own_outputs import read_history
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], f"draw {snakemake.wildcards.bounce}"):
    bounce_figure(read_history(snakemake.input.history), snakemake.params.config["study"],
                  snakemake.wildcards.bounce, snakemake.params.config["contact"]["separation"],
                  [snakemake.output.png])
