"""Snakemake script: a numerics chart (see rule numerics_figure)."""
import logging

from sphereimpact.figures.numerics import stability_figure, work_precision_figure

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
draw = {"work_precision": work_precision_figure, "stability": stability_figure}[snakemake.wildcards.study]
draw(snakemake.input.csv, [snakemake.output.png])
