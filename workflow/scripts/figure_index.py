"""Snakemake script: the index of paper_figures/ with every caption (see rule figure_index)."""
from sphereimpact.figures.captions import write_figure_index
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "figure index"):
    write_figure_index(snakemake.output.md, snakemake.params.runs, snakemake.params.config["primary"]["separation"])
