"""Snakemake script: an own study's bounces and their histories (see rule own_bounces)."""
from sphereimpact.study.own_outputs import write_bounces
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "bounces"):
    config = snakemake.params.config
    write_bounces(config, snakemake.input.ball, snakemake.output.outcomes,
                  dict(zip(config["bounces"], snakemake.output.histories)))
