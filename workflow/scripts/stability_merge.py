"""Snakemake script: the failure-mode studies as one table (see rule stability)."""
from sphereimpact.study.numerics import merge_stability
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "stability studies"):
    merge_stability(snakemake.input.parts, snakemake.output.csv)
