"""Snakemake script: the speed table (see rule speed_table)."""
import logging

from sphereimpact.study.sweeps import write_speed_table

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
write_speed_table(snakemake.params.config, snakemake.output.csv)
