"""Snakemake script: an own study's ball fitted to measured bounces (see rule own_fit)."""
import os

from sphereimpact.study.fitting import study_fit
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "fit the ball to the measured bounces"):
    study_fit(snakemake.params.config, os.path.dirname(snakemake.output.summary))
