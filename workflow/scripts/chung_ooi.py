"""Snakemake script: Chung & Ooi's tests, exact (see rule chung_ooi)."""
import os

from sphereimpact.study.chung_ooi import run_study
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "Chung & Ooi benchmark tests"):
    run_study(os.path.dirname(snakemake.output.rules), snakemake.params.tests, curves_csv=snakemake.input.curves)
