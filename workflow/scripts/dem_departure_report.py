"""Snakemake script: the departure figure and the docs' block (see rule dem_departure_report)."""
from sphereimpact.study.departure import write_report
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "DEM rules' departure: figure and block"):
    write_report(snakemake.input.departure, snakemake.output.png, snakemake.output.md)
