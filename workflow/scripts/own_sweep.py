"""Snakemake script: an own study's speed curve or maps (see rules own_speed, own_maps)."""
from sphereimpact.study.own_outputs import write_maps, write_speed_curve
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], snakemake.rule):
    write = write_speed_curve if snakemake.rule == "own_speed" else write_maps
    write(snakemake.params.config, snakemake.input.ball, snakemake.output.csv)
