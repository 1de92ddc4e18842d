"""Snakemake script: write the published-value report (see rule replicate)."""
import logging

from sphereimpact.study.replication import write_report

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
logging.info("comparing with %s", snakemake.input.published)
write_report(snakemake.params.config, snakemake.input.published, snakemake.input.runs,
             snakemake.output.csv, snakemake.output.md)
