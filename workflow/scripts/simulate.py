"""Snakemake script: simulate one case x force model (see rule simulate)."""
import logging

from sphereimpact.study.runs import run_case

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
case, model = snakemake.wildcards.case, snakemake.wildcards.model
logging.info("simulating case %s with model %s", case, model)
run_case(snakemake.params.config, case, model, snakemake.output.csv, snakemake.output.json)
