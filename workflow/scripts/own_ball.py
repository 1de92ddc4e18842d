"""Snakemake script: an own study's ball, calibrated (see rule own_ball)."""
from sphereimpact.study.own_outputs import write_ball
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "calibrate the ball"):
    fitted = snakemake.input.fitted
    write_ball(snakemake.params.config, snakemake.output.ball, fitted[0] if fitted else None)
