"""Snakemake script: the sweep benchmark (see rule bench_sweep)."""
import logging

from sphereimpact.sweep.bench import run

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
run(snakemake.output.csv)
