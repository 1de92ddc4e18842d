"""Snakemake script: one sweep map (see rule sweep_map)."""
from sphereimpact.figures.sweeps import draw_map
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], f"draw {snakemake.wildcards.map}"):
    draw_map(snakemake.wildcards.map, snakemake.input.angle_speed, snakemake.input.speed,
             snakemake.input.published, snakemake.params.config, [snakemake.output.png], snakemake.input.compliance)
