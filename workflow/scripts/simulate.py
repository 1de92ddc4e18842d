"""Snakemake script: simulate one case x force model (see rule simulate)."""
from sphereimpact.study.runs import run_case
from sphereimpact.study.workflow import job_log

case, model = snakemake.wildcards.case, snakemake.wildcards.model
with job_log(snakemake.log[0], f"simulate case {case} with model {model}"):
    run_case(snakemake.params.config, case, model, snakemake.output.csv, snakemake.output.json)
