"""Snakemake script: draw one chapter figure (see rule figure)."""
import logging

from sphereimpact.figures.paper import make_figure

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
logging.info("drawing %s", snakemake.wildcards.fig)
make_figure(snakemake.wildcards.fig, snakemake.input.runs, snakemake.input.published,
            snakemake.params.separation, [snakemake.output.png, snakemake.output.pdf])
