"""Snakemake script: execute a jupytext notebook to HTML (see rule notebook)."""
import logging

from sphereimpact.study.notebook import execute_to_html

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
logging.info("executing %s", snakemake.input.notebook)
execute_to_html(snakemake.input.notebook, snakemake.output.html, cwd=".")
