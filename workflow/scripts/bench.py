"""Snakemake script: speed-ups at equal accuracy (see rule bench)."""
import logging

from sphereimpact.study.numerics import write_bench

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
write_bench(snakemake.input.csv, snakemake.output.csv)
