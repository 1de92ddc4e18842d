"""Snakemake script: one figure per Chung & Ooi test (see rule chung_ooi_figures)."""
import os

from sphereimpact.figures.chung_ooi import test_figures
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "Chung & Ooi figures"):
    test_figures(os.path.dirname(snakemake.input.rules), snakemake.input.data, snakemake.output.png,
                 snakemake.input.curves)
