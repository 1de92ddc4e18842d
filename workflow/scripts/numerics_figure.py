"""Snakemake script: a numerics chart (see rule numerics_figure)."""
from sphereimpact.figures.numerics import draw_study
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], f"chart {snakemake.wildcards.study}"):
    draw_study(snakemake.wildcards.study, snakemake.input.csv, [snakemake.output.png])
