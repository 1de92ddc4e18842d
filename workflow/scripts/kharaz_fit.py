"""Snakemake script: the Kharaz data fitted (see rule kharaz_fit)."""
import os

from sphereimpact.study.fitting import kharaz_fit
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "fit of the Kharaz data"):
    kharaz_fit(snakemake.params.config, snakemake.input.data, os.path.dirname(snakemake.output.summary))
