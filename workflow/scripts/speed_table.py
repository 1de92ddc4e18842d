"""Snakemake script: the speed table (see rule speed_table)."""
from sphereimpact.study.sweeps import write_speed_table
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "speed table"):
    write_speed_table(snakemake.params.config, snakemake.output.csv)
