"""Snakemake script: an own study's measurement plan (see rule own_plan)."""
import os

from sphereimpact.study.planning import study_plan
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "plan the measurements"):
    study_plan(snakemake.params.config, snakemake.input.ball, os.path.dirname(snakemake.output.summary))
