"""Snakemake script: write the summary table (see rule tabulate)."""
import logging

from sphereimpact.study.tables import write_summary

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
logging.info("tabulating %d runs", len(snakemake.input.runs))
write_summary(snakemake.input.runs, snakemake.output.csv, snakemake.output.md)
