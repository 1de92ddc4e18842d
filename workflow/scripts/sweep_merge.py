"""Snakemake script: concatenate the sweep shards (see rule sweep_merge)."""
import logging

from sphereimpact.study.sweeps import merge

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
logging.info("merging %d shards", len(snakemake.input.shards))
merge(snakemake.input.shards, snakemake.output.csv)
