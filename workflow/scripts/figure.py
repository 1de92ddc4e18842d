"""Snakemake script: draw one chapter figure (see rule figure)."""
from sphereimpact.figures.paper import make_figure
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], f"draw {snakemake.wildcards.fig}"):
    make_figure(snakemake.wildcards.fig, snakemake.input.runs, snakemake.input.published,
                snakemake.params.config["primary"]["separation"], [snakemake.output.png, snakemake.output.pdf])
